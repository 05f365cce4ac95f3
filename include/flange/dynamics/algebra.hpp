// The two algebras the recursive algorithms run in, and which one a scene's
// type calls for.
//
// The algorithms are written once (kinematics.hpp, newton_euler.hpp,
// mass_matrix.hpp, articulated_body.hpp) over the typed quantities of
// math/sparse.hpp. What differs between the algebras is only how the scene's
// constants enter them:
//
//   spatial_algebra   everything in 3-D; what the types rule out (a first
//                     moment or an inertia that the bodies' types make zero or
//                     diagonal, gravity when the World has none) is typed zero
//                     or diagonal.
//   planar_algebra<K> for a planar scene (every rotation about coordinate axis
//                     K, every translation normal to it): linear quantities
//                     (gravity, offsets, first moments, forces) are projected
//                     onto the plane, angular ones (ω, torques) onto K, and of
//                     a rotational inertia only I_KK is kept. What is dropped
//                     changes cut forces only, never q̈.
//
// The typed rules close over each algebra: ω along K rotated about K stays
// along K, an in-plane vector stays in the plane, the cross product of two
// in-plane vectors is along K and that of two vectors along K is zero. So the
// same Newton–Euler code runs planar arithmetic on a planar scene (the old
// planar.hpp is gone), and tests/planar_test.cpp holds the two against each
// other.
#pragma once
#include "flange/detail/inline.hpp"
#include <array>

#include "flange/core/joint.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/math/sparse.hpp"

namespace flange {

struct spatial_algebra {
  static constexpr bool planar = false;
  static constexpr int linear_mask = 7, angular_mask = 7;
};
template <int K>
struct planar_algebra {
  static_assert(K >= 0 && K < 3);
  static constexpr bool planar = true;
  static constexpr int normal = K;
  static constexpr int linear_mask = 7 & ~(1 << K), angular_mask = 1 << K;
};

namespace detail {

/// A linear quantity (force, offset, first moment, acceleration) in algebra A.
template <class A, class T, class D>
FLANGE_INLINE auto linear(const Eigen::MatrixBase<D>& v) {
  return to_svec<A::linear_mask>(Vec3<T>(v.template cast<T>()));
}
/// An angular quantity (torque, angular velocity) in algebra A.
template <class A, class T, class D>
FLANGE_INLINE auto angular(const Eigen::MatrixBase<D>& v) {
  return to_svec<A::angular_mask>(Vec3<T>(v.template cast<T>()));
}

/// The normal axis K if the scene is planar, else −1: every joint that turns
/// turns about one coordinate axis K (and at least one does), every joint
/// moves in the plane normal to K, and every rigid edge turns about K or not
/// at all.
template <class Comp>
constexpr int joint_planar_normal() {  // −2: not a joint
  if constexpr (Comp::kind == role::joint) return Comp::planar_normal();
  else return -2;
}
template <class Comp>
constexpr bool joint_moves_in_plane(int k) {
  if constexpr (Comp::kind == role::joint) return Comp::moves_in_plane(k);
  else return true;
}
template <class S>
constexpr int planar_axis() {
  constexpr auto normals = []<int... C>(std::integer_sequence<int, C...>) {
    return std::array<int, sizeof...(C)>{joint_planar_normal<typename S::template component_type<C>>()...};
  }(std::make_integer_sequence<int, S::n_components>{});
  int k = -1;
  for (const int n : normals) {
    if (n == -1 || (n >= 0 && k >= 0 && n != k)) return -1;
    if (n >= 0) k = n;
  }
  if (k < 0) return -1;
  const bool in_plane = [&]<int... C>(std::integer_sequence<int, C...>) {
    return (true && ... && joint_moves_in_plane<typename S::template component_type<C>>(k));
  }(std::make_integer_sequence<int, S::n_components>{});
  if (!in_plane) return -1;
  for (int s = 0; s < S::topology.n_sets; ++s)
    if (S::tree.set_rotation[s] != -2 && S::tree.set_rotation[s] != k) return -1;
  return k;
}

template <class S, int K = planar_axis<S>()>
struct algebra_of {
  using type = planar_algebra<K>;
};
template <class S>
struct algebra_of<S, -1> {
  using type = spatial_algebra;
};

}  // namespace detail

/// The algebra a scene's type calls for: planar arithmetic for a planar scene.
template <class S>
using algebra_t = typename detail::algebra_of<S>::type;

namespace detail {

/// What the bodies' types say about each link's own inertia, before any
/// number is seen: a body at its link's origin (on the link's root set, no
/// centre-of-mass offset) adds nothing to the first moment and its own J to
/// the rotational inertia; anything else makes both dense.
template <class S>
struct inertia_kinds {
  static constexpr int NL = S::tree.n_links;
  struct table {
    std::array<int, NL> I_kind{};  ///< 0 zero, 1 diagonal, 2 dense
    std::array<bool, NL> h_zero{};
  };
  static constexpr table value = [] {
    table t{};
    for (int L = 0; L < NL; ++L) t.h_zero[L] = true;
    [&]<int... C>(std::integer_sequence<int, C...>) FLANGE_INLINE_LAMBDA {
      (
          [&]() FLANGE_INLINE_LAMBDA {
            using Comp = typename S::template component_type<C>;
            if constexpr (carries_body<Comp>) {
              const int set = S::topology.set_of[S::table.frame_base[C]];
              const int L = S::tree.set_link[set];
              if (L < 0) return;
              const bool at_origin = S::tree.set_parent[set] < 0 && !Comp::has_cm_offset;
              // A body in a link turned to its joint's axis frame
              // (axis_frames.hpp) is turned with it: a diagonal J is not.
              const bool turned = axis_frames<S>::turned[L];
              const int kind = !at_origin ? 2 : Comp::is_point ? 0 : (Comp::is_diagonal && !turned) ? 1 : 2;
              t.I_kind[L] = kind > t.I_kind[L] ? kind : t.I_kind[L];
              t.h_zero[L] = t.h_zero[L] && at_origin;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    return t;
  }();
};

/// A link's mass, first moment and rotational inertia about its origin, typed.
template <class T, class H, class I>
struct rigid_view {
  T m;
  H h;
  I I_o;
};
template <class T, class H, class I>
rigid_view(T, H, I) -> rigid_view<T, H, I>;

/// I_c·(ω, v) for a motion (ω, v): (I·ω + h × v, m·v + ω × h).
template <class I_, class Mot>
FLANGE_INLINE auto inertia_times(const I_& c, const Mot& s) {
  return force_pair{c.I_o * s.ang + cross(c.h, s.lin), c.m * s.lin + cross(s.ang, c.h)};
}

/// A link's own inertia I (the model's record) in algebra A, with what its
/// bodies' types rule out typed away: a first moment known zero (HZero), a
/// rotational inertia of kind IKind (inertia_kinds). A function of the
/// kinds, not of the link.
template <class A, class T, bool HZero, int IKind>
FLANGE_INLINE auto link_inertia_of(const rigid_inertia<double>& I) {
  const T m = T(I.m);
  auto h = [&]() FLANGE_INLINE_LAMBDA {
    if constexpr (HZero) return zero_vec<T>{};
    else return linear<A, T>(I.h);
  }();
  auto rot = [&]() FLANGE_INLINE_LAMBDA {
    if constexpr (A::planar) {
      diag_inertia<T, A::angular_mask> d;
      d.d[A::normal] = T(I.I(A::normal, A::normal));
      return d;
    } else if constexpr (IKind == 0) {
      return zero_inertia{};
    } else if constexpr (IKind == 1) {
      return diag_inertia<T, 7>{{T(I.I(0, 0)), T(I.I(1, 1)), T(I.I(2, 2))}};
    } else {
      return Mat3<T>(I.I.template cast<T>());
    }
  }();
  return rigid_view{m, h, rot};
}

/// Link L's own inertia in algebra A (link_inertia_of, with L's kinds).
template <class A, class T, int L, class S>
FLANGE_INLINE auto link_inertia(const S& scene) {
  constexpr auto K = inertia_kinds<S>::value;
  return link_inertia_of<A, T, K.h_zero[L], K.I_kind[L]>(scene.model().link[L]);
}

/// The type of a composite (subtree) inertia in algebra A: dense in 3-D, the
/// plane's first moment and I_KK in a plane.
template <class A, class T>
struct composite_types {
  using h = svec<T, A::linear_mask>;
  using I = std::conditional_t<A::planar, diag_inertia<T, A::angular_mask>, Mat3<T>>;
};

}  // namespace detail
}  // namespace flange
