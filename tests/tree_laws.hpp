// Laws every scene must obey, checked on one scene at a random state:
//   * the derivative equals the articulated-body algorithm (a second
//     algorithm sharing no code with it but the joint transforms), with its
//     per-link steps both unrolled and as shared functions,
//   * the residual of the components' equations vanishes on the recovered
//     variables,
//   * the power balance: d(kinetic + gravity potential)/dt equals the power of
//     every force element (from its recovered flows and its frames'
//     velocities) plus the power of every joint's own force (input and axis
//     law).
// Before each evaluation the stack is filled with NaN, so a value the
// algorithms read without writing it shows as a wrong answer instead of
// hiding behind a zero that happened to be there.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <flange/dynamics/other_algorithm.hpp>
#include <flange/dynamics/energy.hpp>
#include <flange/dynamics/recover.hpp>
#include <flange/math/dual.hpp>
#include <flange/simulate/system.hpp>

#include "random_params.hpp"

namespace flange::test {

/// Fills the stack below the caller with NaN (what the next call's locals will occupy).
[[gnu::noinline]] inline void poison_stack() {
  volatile double junk[8192];
  for (auto& j : junk) j = std::numeric_limits<double>::quiet_NaN();
  asm volatile("" : : "r"(junk) : "memory");
}

/// A random state: coordinates in [−1.5, 1.5] (kept valid: quaternions
/// normalised), rates in [−2, 2].
template <class S>
typename S::state_type random_state(const S& s, std::mt19937& rng) {
  typename S::state_type x;
  for (int i = 0; i < S::n_q; ++i) x[i] = uniform(rng, -1.5, 1.5);
  for (int i = S::n_q; i < S::n_state; ++i) x[i] = uniform(rng, -2, 2);
  normalize(s, x);
  return x;
}

struct law_errors {
  double algorithms = 0;  ///< max |q̈ − q̈_ABA| / max(1, |q̈|)
  double residual = 0;    ///< max scaled residual
  double power = 0;       ///< max |dE/dt − P| / max(1, Σ|terms|)
};

/// d(kinetic + gravity potential)/dt − (power of force elements and joint forces),
/// and the sum of the magnitudes of the terms (the scale of its round-off).
template <class S, class State>
std::pair<double, double> power_balance(const S& s, double t, const State& x) {
  constexpr int n = S::n_state;
  State f;
  s(x, f, t);
  // ∇E·f exactly: E at x + ε·f with a dual number ε (math/dual.hpp).
  using D = dual<double, 1>;
  std::array<D, n> xd;
  for (int i = 0; i < n; ++i) {
    xd[i] = D(x[i]);
    xd[i].d[0] = f[i];
  }
  // energy() runs no dynamics, so q̈ enters only through f.
  const auto ed = energy(s, D(t), xd);
  const double dE = (ed.kinetic + ed.gravity_potential).d[0];
  const auto sol = recover(s, t, x);
  double P = 0, scale = std::abs(dE);
  detail::for_each_component(s, [&](auto i, const auto& c) {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int I = decltype(i)::value;
    constexpr int fb = S::table.frame_base[I];
    if constexpr (C::kind == role::force) {
      // The element's flows are what the scene exerts on it: its power into
      // the scene is minus their power.
      for (int k = 0; k < int(C::frames.size()); ++k) {
        const auto& fr = sol.frames[fb + k];
        const auto& w = sol.cut[fb + k];
        const double p = -(w.f.dot(fr.R * fr.v) + w.n.dot(fr.w));
        P += p;
        scale += std::abs(p);
      }
    } else if constexpr (C::kind == role::joint) {
      const double* q = sol.q.data() + S::tree.q_offset[I];
      const double* v = sol.v.data() + S::tree.v_offset[I];
      const auto js = state_view<S>(sol.q.data(), sol.v.data());  // drives read joints by name
      if constexpr (requires { c.generalized_force(t, js, q, v, static_cast<double*>(nullptr)); }) {
        std::array<double, C::nv> tau;
        c.generalized_force(t, js, q, v, tau.data());
        for (int k = 0; k < C::nv; ++k) {
          const double p = tau[k] * v[k];
          P += p;
          scale += std::abs(p);
        }
      }
    }
  });
  return {dE - P, std::max(1.0, scale)};
}

template <class S>
void check_laws(const S& s, std::mt19937& rng, law_errors& e, int samples = 10) {
  constexpr int N = S::n_q, NV = S::n_v;
  using X = typename S::state_type;
  for (int k = 0; k < samples; ++k) {
    X x = random_state(s, rng), dx;
    const double t = uniform(rng, 0, 1);
    poison_stack();
    s(x, dx, t);
    std::array<double, NV> aba;
    poison_stack();
    accelerations_other(s, t, x.data(), x.data() + N, aba.data());
    // And the articulated body with its steps as shared functions, which
    // only scenes larger than these would get by default.
    std::array<double, NV> shared;
    poison_stack();
    accelerations_articulated_body<aba_steps::shared>(s, t, x.data(), x.data() + N, shared.data());
    double scale = 1;
    for (int i = 0; i < NV; ++i) scale = std::max(scale, std::abs(dx[N + i]));
    for (int i = 0; i < NV; ++i)
      e.algorithms = std::max({e.algorithms, std::abs(aba[i] - dx[N + i]) / scale,  //
                               std::abs(shared[i] - dx[N + i]) / scale});
    poison_stack();
    const auto sol = recover(s, t, x);
    e.residual = std::max(e.residual, scaled_residual(s, sol));
    const auto [gap, pscale] = power_balance(s, t, x);
    e.power = std::max(e.power, std::abs(gap) / pscale);
  }
}

}  // namespace flange::test
