// The links of a scene's kinematic tree as the recursive algorithms see them:
// compile-time facts about each link (its joint, parent, children, where its
// coordinates sit in the state), the loops over links that the compiler
// unrolls, and each link's motion at q: its joint's motion (core/joint.hpp)
// composed with the constant pose of the frame the joint hangs on.
//
// Link 0 is the World's rigid cluster; link L ≥ 1 is the body behind joint L,
// with its origin at the joint's child-side frame. Links are numbered
// breadth-first, so a parent precedes its children.
#pragma once
#include <array>
#include <tuple>
#include <type_traits>
#include <utility>

#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/dynamics/algebra.hpp"
#include "flange/dynamics/costs.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/math/sincos.hpp"
#include "flange/math/sparse.hpp"

namespace flange::detail {

template <class S, int L>
struct link_info {
  static constexpr auto& tree = S::tree;
  static constexpr int joint = tree.link_joint[L];
  using joint_type = typename S::template component_type<joint>;
  static constexpr int dir = tree.link_dir[L] > 0 ? 1 : -1;
  static constexpr int parent = tree.link_parent[L];
  static constexpr int parent_set = tree.link_parent_set[L];
  static constexpr int q = tree.q_offset[joint];  ///< offset of the joint's coordinates in q
  static constexpr int v = tree.v_offset[joint];  ///< offset of its rates in v (and of its rows in M)
  static constexpr int nq = joint_type::nq, nv = joint_type::nv;
  /// Whether the joint hangs away from its parent link's origin (behind a
  /// rigid edge); if not, that offset is known to be zero.
  static constexpr bool has_offset = tree.set_parent[parent_set] >= 0;
  /// The rotation of the frame it hangs on relative to the parent link: −2
  /// none, k about coordinate axis k, −1 any.
  static constexpr int set_rotation = set_rotation_kind<S>(parent_set);
};

/// The children of link L (links whose parent is L), in order.
template <class S, int L>
constexpr auto children() {
  constexpr int NL = S::tree.n_links;
  constexpr int n = [] {
    int k = 0;
    for (int c = 1; c < NL; ++c) k += S::tree.link_parent[c] == L;
    return k;
  }();
  std::array<int, n> r{};
  int k = 0;
  for (int c = 1; c < NL; ++c)
    if (S::tree.link_parent[c] == L) r[k++] = c;
  return r;
}

/// f(integral_constant<L>) for L = 1 … n_links−1, parents first.
template <class S, class F>
FLANGE_INLINE void for_links(F&& f) {
  [&]<int... L>(std::integer_sequence<int, L...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, L + 1>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}
/// Every joint's neutral configuration (core/joint.hpp) into q[0 … n_q).
template <class S, class T>
void neutral_configuration(const S& scene, T* q) {
  for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, decltype(l)::value>;
    const auto n = scene.template component<LI::joint>().neutral();
    for (int i = 0; i < LI::nq; ++i) q[LI::q + i] = n[i];
  });
}

/// q̇ from (q, v), joint by joint (core/joint.hpp's qdot), into
/// qdot[0 … n_q): the first part of every state derivative.
template <class S, class T>
FLANGE_INLINE void joint_rates(const S& scene, const T* q, const T* v, T* qdot) {
  for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, decltype(l)::value>;
    scene.template component<LI::joint>().qdot(q + LI::q, v + LI::v, qdot + LI::q);
  });
}

/// f(integral_constant<L>) for L = n_links−1 … 1, children first.
template <class S, class F>
FLANGE_INLINE void for_links_reverse(F&& f) {
  [&]<int... L>(std::integer_sequence<int, L...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, S::tree.n_links - 1 - L>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}
/// f(integral_constant<C>) for each child C of link L.
template <class S, int L, class F>
FLANGE_INLINE void for_children(F&& f) {
  constexpr auto c = children<S, L>();
  [&]<std::size_t... I>(std::index_sequence<I...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, c[I]>{}), ...);
  }(std::make_index_sequence<c.size()>{});
}

/// The constant pose of a connection set relative to its link: the rotation
/// (identity, about a coordinate axis, or any) and the offset (zero for the
/// link's root set), typed, in algebra A.
template <class A, class T, class S, int Set>
FLANGE_INLINE auto set_rotation(const S& scene) {
  constexpr int kind = set_rotation_kind<S>(Set);
  if constexpr (kind == -2) {
    return identity_rotation{};
  } else if constexpr (kind >= 0) {
    constexpr int j = (kind + 1) % 3, k = (kind + 2) % 3;
    const Mat3d& R = scene.model().set_rotation[Set];
    return coordinate_rotation<T, kind>{T(R(j, j)), T(R(j, k))};
  } else {
    return Mat3<T>(scene.model().set_rotation[Set].template cast<T>());
  }
}
template <class A, class T, class S, int Set>
FLANGE_INLINE auto set_offset(const S& scene) {
  if constexpr (S::tree.set_parent[Set] < 0) return zero_vec<T>{};
  else return linear<A, T>(scene.model().set_offset[Set]);
}

/// A link's motion: its joint's motion jm composed with the pose (Es, ps) of
/// the frame the joint hangs on, so that E() rotates parent-link coordinates
/// into child coordinates and p is the child origin in parent-link
/// coordinates. Where the frame is not turned (no FixedRotation on the way),
/// E() is the joint's own rotation, not a copy.
template <class JM, class ES, class P>
struct link_motion {
  using set_rotation_type = ES;
  JM jm;
  ES Es;
  std::conditional_t<is_identity_rotation<ES>, identity_rotation,
                     decltype(compose(std::declval<const JM&>().E, std::declval<const ES&>()))>
      E_;
  P p;
  FLANGE_INLINE const auto& E() const {
    if constexpr (is_identity_rotation<ES>) return jm.E;
    else return E_;
  }
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    return jm.w(v);
  }
  template <class V>
  FLANGE_INLINE auto pd(const V& v) const {
    return rot_t(Es, jm.pd(v));
  }
  template <class V>
  FLANGE_INLINE auto w_bias(const V& v) const {
    return jm.w_bias(v);
  }
  template <class V>
  FLANGE_INLINE auto pd_bias(const V& v) const {
    return rot_t(Es, jm.pd_bias(v));
  }
  template <class N, class F>
  FLANGE_INLINE auto project(const N& n, const F& f) const {
    return jm.project(n, f);
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    return jm.template col<K>();
  }
  template <class T>
  FLANGE_INLINE void turn_rates(const T* r, T* out) const {
    jm.turn_rates(r, out);
  }
  template <class T>
  FLANGE_INLINE void unturn_rates(const T* a, T* out) const {
    jm.unturn_rates(a, out);
  }
};

/// A link's motion from its joint's motion jm and the rotation Es of what the
/// joint hangs on, in the coordinates the link computes in.
template <class A, class T, int L, class S, class JM, class ES>
FLANGE_INLINE auto link_motion_of(const S& scene, JM jm, ES Es) {
  auto p = set_offset<A, T, S, link_info<S, L>::parent_set>(scene) + rot_t(Es, jm.p);
  using M = link_motion<JM, ES, decltype(p)>;
  if constexpr (is_identity_rotation<ES>) {
    return M{std::move(jm), Es, {}, p};
  } else {
    auto E = compose(jm.E, Es);
    return M{std::move(jm), Es, E, p};
  }
}

/// Whether link L's joint turns by one angle (core/joint.hpp: angle_joint)
/// whose cosine and sine this motion needs: those links get theirs from one
/// call for all (link_motions).
template <class S, int L, bool NeedRotation>
constexpr bool takes_angle() {
  return angle_joint<typename link_info<S, L>::joint_type> && NeedRotation;
}
/// The angle link L's joint turns by: its angle coordinate, plus θ₀ where the
/// link is aligned with its parent (axis_frames.hpp).
template <class T, int L, class S>
FLANGE_INLINE T link_angle(const S& scene, const T* q) {
  using LI = link_info<S, L>;
  const T& phi = q[LI::q + LI::joint_type::angle_coordinate];
  if constexpr (axis_aligned<S, L>) return phi + T(LI::dir * scene.model().link_align[L].offset);
  else return phi;
}
/// Link L's joint's motion with the cosine and sine of its link_angle given,
/// in the coordinates link L computes in: in the joint's axis frame where
/// the link computes in it (axis_frames.hpp).
template <class T, int L, class S>
FLANGE_INLINE auto joint_motion_with(const S& scene, const T* q, const cos_sin<T>& a) {
  using LI = link_info<S, L>;
  const auto& joint = scene.template component<LI::joint>();
  if constexpr (axis_framed<S, L>) return joint.template motion_in_axis_frame<T, LI::dir>(q + LI::q, a);
  else return joint.template motion<T, LI::dir>(q + LI::q, a);
}
/// Link L's joint's motion at q, in the coordinates link L computes in.
template <class T, int L, bool NeedRotation, class S>
FLANGE_INLINE auto joint_motion_at(const S& scene, const T* q) {
  using LI = link_info<S, L>;
  const auto& joint = scene.template component<LI::joint>();
  if constexpr (takes_angle<S, L, NeedRotation>())
    return joint_motion_with<T, L>(scene, q, cos_sin_of(link_angle<T, L>(scene, q)));
  else if constexpr (axis_framed<S, L>)
    return joint.template motion_in_axis_frame<T, LI::dir, NeedRotation>(q + LI::q);
  else
    return joint.template motion<T, LI::dir, NeedRotation>(q + LI::q);
}

/// Link L's motion from its joint's motion jm: jm after the rotation of the
/// frame the joint hangs on; after the turn C_L where the link computes in
/// its axis frame, as R_x(α) where the link is aligned with its parent.
template <class A, class T, int L, class S, class JM>
FLANGE_INLINE auto link_motion_from(const S& scene, JM jm) {
  using LI = link_info<S, L>;
  if constexpr (axis_aligned<S, L>) {
    const auto& al = scene.model().link_align[L];
    return link_motion_of<A, T, L>(scene, std::move(jm), coordinate_rotation<T, 0>{T(al.c), T(al.s)});
  } else if constexpr (axis_framed<S, L>) {
    return link_motion_of<A, T, L>(scene, std::move(jm), Mat3<T>(scene.model().link_turn[L].template cast<T>()));
  } else {
    return link_motion_of<A, T, L>(scene, std::move(jm), set_rotation<A, T, S, LI::parent_set>(scene));
  }
}

/// Link L's motion at q. The joint's motion first, in a statement of its
/// own: its sine and cosine are a call, and what is loaded before a call and
/// used after it is kept across it in memory.
template <class A, class T, int L, bool NeedRotation, class S>
FLANGE_INLINE auto make_link_motion(const S& scene, const T* q) {
  auto jm = joint_motion_at<T, L, NeedRotation>(scene, q);
  return link_motion_from<A, T, L>(scene, std::move(jm));
}

/// Whether link L turns its parent's coordinates by a general 3 × 3 rotation
/// (a run-time axis, a free orientation) rather than a typed one.
template <class S, int L>
constexpr bool general_rotation() {
  using M = decltype(make_link_motion<spatial_algebra, double, L, true>(std::declval<const S&>(),
                                                                         static_cast<const double*>(nullptr)));
  return std::is_same_v<std::remove_cvref_t<decltype(std::declval<const M&>().E())>, Mat3<double>>;
}

/// The same links' motions with the set offsets in 3-D: for the pose pass of
/// a planar scene, whose own motions hold in-plane offsets only. The joints'
/// motions (and their sines and cosines) are reused, not recomputed.
template <class T, class S, class Motions>
FLANGE_INLINE auto spatial_offsets(const S& scene, const Motions& motions) {
  return [&]<int... L>(std::integer_sequence<int, L...>) FLANGE_INLINE_LAMBDA {
    return std::make_tuple([&]() FLANGE_INLINE_LAMBDA {
      using LI = link_info<S, L + 1>;
      const auto& m = std::get<L>(motions);
      auto p = set_offset<spatial_algebra, T, S, LI::parent_set>(scene) + rot_t(m.Es, m.jm.p);
      return link_motion<std::remove_cvref_t<decltype(m.jm)>, std::remove_cvref_t<decltype(m.Es)>, decltype(p)>{
          m.jm, m.Es, m.E_, p};
    }()...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}

/// Whether link L's rotation is applied to anything that is not zero: always
/// behind another link (its subtree's wrench and inertia are carried up) or
/// with a position pass; on the World only when gravity or the joint's own
/// bias acceleration reaches it. Otherwise its sine and cosine are not even
/// computed (a gravity-free arm does no trigonometry).
template <class S, int L, bool HasPositionPass>
constexpr bool need_rotation() {
  using LI = link_info<S, L>;
  if constexpr (LI::parent != 0 || HasPositionPass || S::has_gravity) {
    return true;
  } else {
    using JM = decltype(make_link_motion<spatial_algebra, double, L, true>(std::declval<const S&>(),
                                                                          static_cast<const double*>(nullptr))
                            .jm);
    using Bias = decltype(std::declval<const JM&>().pd_bias(static_cast<const double*>(nullptr)));
    return !is_zero_vec<Bias>;
  }
}

/// The links that take their angle's cosine and sine from one call
/// (takes_angle), in order, and each link's place among them (−1: none).
/// Fewer than batch_angles_from (costs.hpp) take theirs one at a time.
template <class S, bool HasPositionPass>
struct angle_links {
  static constexpr int NL = S::tree.n_links;
  static constexpr std::array<int, NL> place = [] {
    std::array<bool, NL> takes{};
    [&]<int... L>(std::integer_sequence<int, L...>) {
      ((takes[L + 1] = takes_angle<S, L + 1, need_rotation<S, L + 1, HasPositionPass>()>()), ...);
    }(std::make_integer_sequence<int, NL - 1>{});
    std::array<int, NL> r{};
    int k = 0;
    for (int L = 0; L < NL; ++L) r[L] = takes[L] ? k++ : -1;
    return r;
  }();
  static constexpr int count = [] {
    int k = 0;
    for (const int p : place) k += p >= 0;
    return k;
  }();
};

/// The motions of all links at q, as a tuple (link L at L − 1).
template <class A, class T, bool HasPositionPass, class S>
FLANGE_INLINE auto link_motions(const S& scene, const T* q) {
  // Every joint's motion first (the sines and cosines, calls), then the
  // links' offsets and turns: loaded between two calls, they would be kept
  // across the later ones in memory.
  using AL = angle_links<S, HasPositionPass>;
  if constexpr (std::is_same_v<T, double> && AL::count >= batch_angles_from) {
    // The angles' cosines and sines in one call (math/sincos.hpp), then the
    // motions from them.
    cos_sin_batch<AL::count> cs;
    for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      constexpr int L = decltype(l)::value;
      if constexpr (AL::place[L] >= 0) cs.a[AL::place[L]] = link_angle<T, L>(scene, q);
    });
    cs.compute();
    return [&]<int... L>(std::integer_sequence<int, L...>) FLANGE_INLINE_LAMBDA {
      return std::make_tuple(link_motion_from<A, T, L + 1>(scene, [&]() FLANGE_INLINE_LAMBDA {
        if constexpr (AL::place[L + 1] >= 0) return joint_motion_with<T, L + 1>(scene, q, cs[AL::place[L + 1]]);
        else return joint_motion_at<T, L + 1, need_rotation<S, L + 1, HasPositionPass>()>(scene, q);
      }())...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  } else {
    return [&]<int... L>(std::integer_sequence<int, L...>) FLANGE_INLINE_LAMBDA {
      std::tuple jm{joint_motion_at<T, L + 1, need_rotation<S, L + 1, HasPositionPass>()>(scene, q)...};
      return std::make_tuple(link_motion_from<A, T, L + 1>(scene, std::move(std::get<L>(jm)))...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  }
}

}  // namespace flange::detail
