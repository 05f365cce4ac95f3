// Forward kinematics over the tree, and the depth-first walk every recursive
// algorithm is built on.
//
// walk<L>(ctx, d) visits link L with the value d passed down from its parent
// (ctx.at<L>(d) starts what it will return), then each child C with
// ctx.down<L, C>(d), gathers what each child returns with ctx.gather<L, C>,
// and returns ctx.leave<L>(d, …) to its parent. A pass is a
// context: Newton–Euler passes kinematics down and wrenches up; the mass
// matrix passes composite inertias up; recovery passes world poses down. The
// walk is unrolled at compile time, so each link is a straight-line block,
// and every value has its own type (math/sparse.hpp): what is zero for a link
// is never computed.
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
auto base_kinematics(const S& scene) {
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

// ------------------------------------------------------------ the walk

template <class S, int L, class Ctx, class D>
auto walk(Ctx& ctx, const D& down);

template <class S, int L, class Ctx, class D>
[[gnu::noinline]] auto walk_call(Ctx& ctx, const D& down) {
  return walk<S, L>(ctx, down);
}
/// The walk of child L's subtree: inlined, or a call when split_links<S>
/// (links.hpp, the rule of for_links_split). Inlined, a long chain's walk
/// nests every link's step into one function, which took the optimiser more
/// than 6 GB at 128 links.
template <class S, int L, class Ctx, class D>
FLANGE_INLINE auto walk_subtree(Ctx& ctx, const D& down) {
  if constexpr (split_links<S>) return walk_call<S, L>(ctx, down);
  else return walk<S, L>(ctx, down);
}

template <class S, int L, std::size_t I, class Ctx, class D, class Acc>
FLANGE_INLINE auto walk_children(Ctx& ctx, const D& down, Acc acc) {
  constexpr auto cs = children<S, L>();
  if constexpr (I == cs.size()) {
    return acc;
  } else {
    constexpr int C = cs[I];
    auto r = walk_subtree<S, C>(ctx, ctx.template down<L, C>(down));
    return walk_children<S, L, I + 1>(ctx, down, ctx.template gather<L, C>(std::move(acc), std::move(r)));
  }
}

template <class S, int L, class Ctx, class D>
FLANGE_INLINE auto walk(Ctx& ctx, const D& down) {
  return ctx.template leave<L>(down, walk_children<S, L, 0>(ctx, down, ctx.template at<L>(down)));
}

/// Nothing to pass up.
struct nothing {};

// ------------------------------------------------------------ world poses

/// A link's pose and motion in the world, dense: what force elements between
/// frames and recovery need (the recursive algorithms themselves do not).
template <class T>
struct link_pose {
  Mat3<T> R;  ///< rotates world into link coordinates
  Vec3<T> r;  ///< origin, world coordinates
  Vec3<T> v;  ///< origin's velocity, world coordinates
  Vec3<T> w;  ///< ω, link coordinates
};

/// The pose pass: R, r, ṙ and ω of every link (link 0 is the World).
template <class S, class T, class Motions>
struct pose_pass {
  const Motions& motions;
  const T* v;
  std::array<link_pose<T>, S::tree.n_links>& out;

  template <int L>
  nothing at(const link_pose<T>& d) {
    out[L] = d;
    return {};
  }
  template <int L, int C>
  link_pose<T> down(const link_pose<T>& P) {
    const auto& m = std::get<C - 1>(motions);
    const T* vc = v + link_info<S, C>::v;
    const Vec3<T> p = m.p.dense();
    link_pose<T> c;
    if constexpr (L == 0) {  // on the World: R_P = 1, r_P = ṙ_P = ω_P = 0
      c.R = to_matrix<T>(m.E());
      c.r = p;
      c.v = m.pd(vc).dense();
      c.w = m.w(vc).dense();
    } else {
      c.R = to_matrix<T>(m.E()) * P.R;
      c.r = P.r + P.R.transpose() * p;
      c.v = P.v + P.R.transpose() * (P.w.cross(p) + m.pd(vc).dense());
      c.w = rot(m.E(), to_svec(P.w)).dense() + m.w(vc).dense();
    }
    return c;
  }
  template <int, int>
  nothing gather(nothing, nothing) {
    return {};
  }
  template <int, class D>
  nothing leave(const D&, nothing) {
    return {};
  }
};

/// World poses and velocities of every link at (q, v); motions in the spatial algebra.
template <class S, class T, class Motions>
FLANGE_INLINE std::array<link_pose<T>, S::tree.n_links> link_poses(const Motions& motions, const T* v) {
  std::array<link_pose<T>, S::tree.n_links> out;
  pose_pass<S, T, Motions> ctx{motions, v, out};
  walk<S, 0>(ctx, link_pose<T>{Mat3<T>::Identity(), Vec3<T>::Zero(), Vec3<T>::Zero(), Vec3<T>::Zero()});
  return out;
}

}  // namespace flange::detail
