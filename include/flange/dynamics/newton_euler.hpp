// Inverse dynamics by recursive Newton–Euler: the generalized forces
// τ = ID(q, v, v̇) that give the joints the accelerations v̇, with gravity
// and the force elements' loads. At v̇ = 0 (no_rates) it is the bias b of
// M(q)·v̇ = τ − b (forward_dynamics.hpp).
//
// Going down the tree (kinematics.hpp) each link gets ω, ω̇ and its origin's
// acceleration a (with −g); coming back up each returns the wrench its
// subtree needs at its origin, link coordinates:
//
//   f = m·a + ω̇ × h + ω × (ω × h) − f_ext       (h = m·c, the first moment)
//   n = I·ω̇ + ω × I·ω + h × a − n_ext          (I about the origin)
//   plus each child's wrench carried up: (Eᵀ·n_C + p × Eᵀ·f_C, Eᵀ·f_C)
//
// and its joint takes τ = Sᵀ·(n, f). Every quantity is typed
// (math/sparse.hpp), so a zero first moment, a diagonal inertia, ω along one
// axis or no gravity remove their arithmetic; in the planar algebra
// (algebra.hpp) the same code is planar arithmetic.
#pragma once
#include <array>

#include "flange/detail/inline.hpp"

#include "flange/dynamics/external.hpp"
#include "flange/dynamics/kinematics.hpp"

namespace flange::detail {

template <class N1, class F1, class N2, class F2>
FLANGE_INLINE auto operator+(const force_pair<N1, F1>& a, const force_pair<N2, F2>& b) {
  return force_pair{a.n + b.n, a.f + b.f};
}

/// A wrench at a child link's origin (child coordinates) carried to its
/// parent's origin (parent coordinates) through the child's motion m.
template <class M, class N, class F>
FLANGE_INLINE auto carry_up(const M& m, const force_pair<N, F>& w) {
  // One expression, not a named f copied into the pair: from a named f GCC
  // kept the pair in memory in the mass-matrix pass, where only its
  // projection on the parent's joint is used. The rotation is formed once
  // (CSE).
  return force_pair{rot_t(m.E(), w.n) + cross(m.p, rot_t(m.E(), w.f)), rot_t(m.E(), w.f)};
}

/// The wrench a link of inertia I needs for its own motion k: inertia,
/// gravity (in a), minus the force elements' loads on it (n_ext, f_ext when
/// Torque, Force say the link has them). A function of the link's kinds, not
/// of the link.
template <class A, class T, bool Torque, bool Force, class I, class K>
FLANGE_INLINE auto own_wrench_of(const I& inertia, const K& k, const Vec3<T>& n_ext, const Vec3<T>& f_ext) {
  const auto f = inertia.m * k.a + cross(k.wd, inertia.h) + double_cross(k.w, inertia.h);
  const auto n = inertia.I_o * k.wd + cross(k.w, inertia.I_o * k.w) + cross(inertia.h, k.a);
  auto with_force = [&]() FLANGE_INLINE_LAMBDA {
    if constexpr (Force) return f - linear<A, T>(f_ext);
    else return f;
  };
  auto with_torque = [&]() FLANGE_INLINE_LAMBDA {
    if constexpr (Torque) return n - angular<A, T>(n_ext);
    else return n;
  };
  return force_pair{with_torque(), with_force()};
}

/// The wrench link L needs for its own motion k (own_wrench_of).
template <class A, class T, int L, class S, class K>
FLANGE_INLINE auto own_wrench(const S& scene, const K& k, const link_loads<S, T>& n_ext, const link_loads<S, T>& f_ext) {
  constexpr auto F = load_flags<S>::value;
  return own_wrench_of<A, T, F.torque[L], F.force[L]>(link_inertia<A, T, L>(scene), k, n_ext[L], f_ext[L]);
}

/// The Newton–Euler pass as a walk (kinematics.hpp): kinematics down,
/// wrenches up, τ written per joint.
template <class A, class S, class T, class Motions, class V, class VD>
struct inverse_dynamics_pass {
  const S& scene;
  const Motions& motions;
  V v;
  VD vd;
  const link_loads<S, T>& n_ext;
  const link_loads<S, T>& f_ext;
  T* tau;

  template <int L, class K>
  FLANGE_INLINE auto at(const K& k) {
    if constexpr (L == 0) return nothing{};
    else return own_wrench<A, T, L>(scene, k, n_ext, f_ext);
  }
  template <int L, int C, class K>
  FLANGE_INLINE auto down(const K& k) {
    constexpr int o = link_info<S, C>::v;
    return forward_step<T>(k, std::get<C - 1>(motions), rates_at<o>(v), rates_at<o>(vd));
  }
  template <int L, int C, class W, class WC>
  FLANGE_INLINE auto gather(W acc, const WC& child) {
    if constexpr (L == 0) return acc;
    else return acc + carry_up(std::get<C - 1>(motions), child);
  }
  template <int L, class K, class W>
  FLANGE_INLINE W leave(const K&, W acc) {
    if constexpr (L != 0) {
      using LI = link_info<S, L>;
      const auto g = std::get<L - 1>(motions).project(acc.n, acc.f);
      for (int i = 0; i < LI::nv; ++i) tau[LI::v + i] = g[i];
    }
    return acc;
  }
};

/// τ = ID(q, v, v̇) into tau (n_v entries): the generalized forces for rates v
/// and accelerations vd (no_rates for the bias), with gravity and the loads
/// n_ext, f_ext (external.hpp). motions: link_motions at q in algebra A.
template <class A, class S, class T, class Motions, class V, class VD>
FLANGE_INLINE void inverse_dynamics(const S& scene, const Motions& motions, const V& v, const VD& vd, const link_loads<S, T>& n_ext,
                      const link_loads<S, T>& f_ext, T* tau) {
  inverse_dynamics_pass<A, S, T, Motions, V, VD> ctx{scene, motions, v, vd, n_ext, f_ext, tau};
  walk<S, 0>(ctx, base_kinematics<A, T>(scene));
}

}  // namespace flange::detail
