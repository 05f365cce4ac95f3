// Forward kinematics over the tree: a link's kinematics from its parent's
// (forward_step); the pose pass, a walk (schedule.hpp) that passes world
// poses down; the accelerations pass (recovery at v̇, loop constraints'
// biases at v̇ = 0); and a frame's motion from its link's (point_position,
// point_velocity, point_acceleration). The other walks are passes of their
// own: Newton–Euler passes kinematics down and wrenches up (newton_euler.hpp),
// the mass matrix composite inertias up (mass_matrix.hpp). Every value has
// its own type (math/sparse.hpp): what is zero for a link is never computed.
//
// Per link, in link coordinates at its origin, with the World's gravity as a
// base acceleration −g ("classic" accelerations, no linear velocity needed):
//
//   ω  = E·ω_P + S_ω·v
//   ω̇  = E·ω̇_P + (E·ω_P) × S_ω·v + S_ω·v̇ + Ṡ_ω·v
//   a  = E·(a_P + ω̇_P × p + ω_P × (ω_P × p) + 2·ω_P × ṗ + S_v·v̇ + Ṡ_v·v)
//
// (E, p, ṗ = S_v·v: the link's motion, links.hpp).
#pragma once
#include <array>

#include "flange/detail/inline.hpp"
#include <utility>

#include "flange/core/frame_kinematics.hpp"
#include "flange/dynamics/links.hpp"
#include "flange/dynamics/schedule.hpp"

namespace flange::detail {

/// ω, ω̇ and the origin's acceleration a (with −g), link coordinates, typed.
template <class W, class WD, class A_>
struct link_kinematics {
  W w;
  WD wd;
  A_ a;
};
template <class W, class WD, class A_>
link_kinematics(W, WD, A_) -> link_kinematics<W, WD, A_>;

/// The joint's rates within v (a pointer), or no_rates.
template <int Offset, class V>
FLANGE_INLINE auto rates_at(const V& v) {
  if constexpr (is_no_rates<V>) return no_rates{};
  else return v + Offset;
}

/// The World's kinematics: at rest, accelerating by −g (or not at all).
template <class A, class T, class S>
FLANGE_INLINE auto base_kinematics(const S& scene) {
  if constexpr (S::has_gravity) {
    return link_kinematics{zero_vec<T>{}, zero_vec<T>{}, linear<A, T>(Vec3<T>(scene.model().minus_g.template cast<T>()))};
  } else {
    (void)scene;
    return link_kinematics{zero_vec<T>{}, zero_vec<T>{}, zero_vec<T>{}};
  }
}

/// Link kinematics from its parent's and its motion m, at rates v and v̇.
template <class T, class K, class M, class V, class VD>
FLANGE_INLINE auto forward_step(const K& P, const M& m, const V& v, const VD& vd) {
  const auto wP = rot(m.E(), P.w);
  const auto wr = m.w(v);
  const auto wd = rot(m.E(), P.wd) + cross(wP, wr) + m.w(vd) + m.w_bias(v);
  const auto ap = P.a + cross(P.wd, m.p) + double_cross(P.w, m.p) + T(2) * cross(P.w, m.pd(v)) + m.pd(vd) +
                  m.pd_bias(v);
  return link_kinematics{wP + wr, wd, rot(m.E(), ap)};
}

// ------------------------------------------------------------ world poses

/// Where a link pose gives its origin's velocity: in world coordinates
/// (recovery, energies, loop constraints), or in the link's own (force
/// elements: the pass then turns it by each joint's sparse E, not by the
/// dense world rotation, and a half-space meets the link in its coordinates).
enum class velocity_in { world, link };

/// A link's pose and motion in the world, dense: what force elements between
/// frames and recovery need (the recursive algorithms themselves do not).
template <class T, velocity_in V = velocity_in::world>
struct link_pose {
  Mat3<T> R;  ///< rotates world into link coordinates
  Vec3<T> r;  ///< origin, world coordinates
  Vec3<T> v;  ///< origin's velocity, world coordinates (link coordinates when V is link)
  Vec3<T> w;  ///< ω, link coordinates
};

/// A link pose's rotation in the form the scene's type allows: about axis K
/// when K ≥ 0 (a planar scene, where every link turns about K: algebra.hpp),
/// as its cosine and sine; dense otherwise.
template <int K, class T, velocity_in V>
FLANGE_INLINE decltype(auto) typed_rotation(const link_pose<T, V>& P) {
  if constexpr (K >= 0) {
    constexpr int j = (K + 1) % 3, k = (K + 2) % 3;
    return coordinate_rotation<T, K>{P.R(j, j), P.R(j, k)};
  } else {
    return (P.R);
  }
}
/// An angular velocity or acceleration in the form the scene's type allows:
/// along axis K when K ≥ 0 (a planar scene), dense otherwise.
template <int K, class T>
FLANGE_INLINE auto typed_angular(const Vec3<T>& w) {
  if constexpr (K >= 0) return to_svec<1 << K>(w);
  else return to_svec(w);
}

/// Every link of the tree: link_poses' Keep, a type whose value marks the
/// links to write out. (A type: with the array itself as the template
/// argument, the g++ 12 build of tests/hard_mass_ratio_test.cpp wrote out
/// other links than the ones marked.)
template <class S>
struct all_links {
  static constexpr std::array<bool, S::tree.n_links> value = [] {
    std::array<bool, S::tree.n_links> k{};
    k.fill(true);
    return k;
  }();
};

/// The pose pass: R, r, ṙ and ω of every link (link 0 is the World), each
/// computed in its place in out and read there by its children, not passed
/// down by value and copied into out (a pose of dual numbers in six
/// directions is a kilobyte). Keep::value marks the links the caller
/// reads; the pass writes them all.
template <class S, class T, class Motions, class Keep, velocity_in V>
struct pose_pass : down_only_walk {
  using pose = link_pose<T, V>;
  const Motions& motions;
  const T* v;
  std::array<pose, S::tree.n_links>& out;

  template <int L>
  nothing at(const pose& d) {
    if constexpr (L == 0 && Keep::value[0]) out[0] = d;  // the others are there already (down)
    return {};
  }
  template <int L, int C>
  const pose& down(const pose& P) {
    const auto& m = std::get<C - 1>(motions);
    const T* vc = v + link_info<S, C>::v;
    pose& c = out[C];
    if constexpr (L == 0) {  // on the World: R_P = 1, r_P = ṙ_P = ω_P = 0
      c.R = to_matrix<T>(m.E());
      c.r = m.p.dense();
      if constexpr (V == velocity_in::link) c.v = rot(m.E(), m.pd(vc)).dense();
      else c.v = m.pd(vc).dense();
      c.w = m.w(vc).dense();
    } else {
      // Each product in its sparse form (a revolute about a coordinate axis
      // turns two rows of R; an offset along one axis reads one column; in
      // a planar scene P's R is a turn about the normal and ω lies along it).
      constexpr int K = planar_axis<S>();
      using E = std::remove_cvref_t<decltype(m.E())>;
      if constexpr (K >= 0 && (is_identity_rotation<E> || std::is_same_v<E, coordinate_rotation<T, K>>)) {
        c.R = to_matrix<T>(compose(m.E(), typed_rotation<K>(P)));  // in the plane both turn about K
      } else {
        for (int j = 0; j < 3; ++j) c.R.col(j) = rot(m.E(), to_svec(Vec3<T>(P.R.col(j)))).dense();
      }
      const auto& R = typed_rotation<K>(P);
      const auto w = typed_angular<K>(P.w);
      c.r = P.r + rot_t(R, m.p).dense();
      if constexpr (V == velocity_in::link)
        c.v = rot(m.E(), to_svec(Vec3<T>(P.v + (cross(w, m.p) + m.pd(vc)).dense()))).dense();
      else
        c.v = P.v + rot_t(R, cross(w, m.p) + m.pd(vc)).dense();
      c.w = rot(m.E(), w).dense() + m.w(vc).dense();
    }
    return c;
  }
};

/// World poses and velocities of the links at (q, v) (Keep::value: those
/// the caller reads), the velocities in V's coordinates; motions in the
/// spatial algebra.
template <class S, class T, class Keep = all_links<S>, velocity_in V = velocity_in::world, class Motions>
FLANGE_INLINE std::array<link_pose<T, V>, S::tree.n_links> link_poses(const Motions& motions, const T* v) {
  std::array<link_pose<T, V>, S::tree.n_links> out;
  pose_pass<S, T, Motions, Keep, V> ctx{{}, motions, v, out};
  walk<S, 0>(ctx, link_pose<T, V>{Mat3<T>::Identity(), Vec3<T>::Zero(), Vec3<T>::Zero(), Vec3<T>::Zero()});
  return out;
}

// ------------------------------------------------------------ accelerations

/// The accelerations pass: ω̇ and a of every link (link coordinates, dense)
/// at rates v and v̇ (a pointer, or no_rates: v̇ = 0), by forward_step.
template <class S, class T, class Motions, class VD>
struct acceleration_pass : down_only_walk {
  const Motions& motions;
  const T* v;
  VD vdot;
  std::array<Vec3<T>, S::tree.n_links>& wd;
  std::array<Vec3<T>, S::tree.n_links>& a;

  template <int L, class K>
  nothing at(const K& k) {
    wd[L] = k.wd.dense();
    a[L] = k.a.dense();
    return {};
  }
  template <int L, int C, class K>
  auto down(const K& k) {
    constexpr int o = link_info<S, C>::v;
    return forward_step<T>(k, std::get<C - 1>(motions), v + o, rates_at<o>(vdot));
  }
};

/// ω̇ and a of every link at (v, v̇) from the base's kinematics (the World's:
/// base_kinematics, with −g; or at rest): link coordinates, dense.
template <class S, class T, class Motions, class VD, class Base>
void link_accelerations(const Motions& motions, const T* v, const VD& vdot, const Base& base,
                        std::array<Vec3<T>, S::tree.n_links>& wd, std::array<Vec3<T>, S::tree.n_links>& a) {
  acceleration_pass<S, T, Motions, VD> ctx{{}, motions, v, vdot, wd, a};
  walk<S, 0>(ctx, base);
}

// ------------------------------------------------------------ frames on links

/// A point fixed in a link at p (link coordinates), the link at pose L: its
/// position, velocity and (from the link's ω̇ and a, link coordinates) its
/// acceleration, world coordinates. Every frame's motion is its link's
/// through these (recovery, energies, force elements, loop constraints).
/// K ≥ 0: the scene is planar about axis K (typed_rotation), which spares
/// the arithmetic out of the plane.
template <int K = -1, class T, velocity_in V>
FLANGE_INLINE Vec3<T> point_position(const link_pose<T, V>& L, const Vec3<T>& p) {
  if constexpr (K >= 0) return L.r + rot_t(typed_rotation<K>(L), to_svec(p)).dense();
  else return L.r + L.R.transpose() * p;
}
template <int K = -1, class T>
FLANGE_INLINE Vec3<T> point_velocity(const link_pose<T>& L, const Vec3<T>& p) {
  if constexpr (K >= 0) return L.v + rot_t(typed_rotation<K>(L), cross(typed_angular<K>(L.w), to_svec(p))).dense();
  else return L.v + L.R.transpose() * L.w.cross(p);
}
/// The same from a pose with its velocity in link coordinates.
template <class T>
FLANGE_INLINE Vec3<T> point_velocity(const link_pose<T, velocity_in::link>& L, const Vec3<T>& p) {
  return L.R.transpose() * (L.v + L.w.cross(p));
}
/// An angular velocity or acceleration w in link coordinates, in the world's.
template <int K = -1, class T>
FLANGE_INLINE Vec3<T> angular_in_world(const link_pose<T>& L, const Vec3<T>& w) {
  if constexpr (K >= 0) return rot_t(typed_rotation<K>(L), typed_angular<K>(w)).dense();
  else return L.R.transpose() * w;
}
template <int K = -1, class T>
FLANGE_INLINE Vec3<T> point_acceleration(const link_pose<T>& L, const Vec3<T>& p, const Vec3<T>& wd, const Vec3<T>& a) {
  if constexpr (K >= 0) {
    const auto w = typed_angular<K>(L.w);
    const auto P = to_svec(p);
    return rot_t(typed_rotation<K>(L), to_svec(a) + cross(typed_angular<K>(wd), P) + cross(w, cross(w, P))).dense();
  } else {
    return L.R.transpose() * (a + wd.cross(p) + L.w.cross(L.w.cross(p)));
  }
}

}  // namespace flange::detail
