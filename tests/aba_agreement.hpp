// The articulated body's two forms of steps (unrolled, shared) against
// Newton–Euler + M, which shares none of their passes, over random states.
#pragma once
#include <flange/dynamics/forward_dynamics.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace flange::test {

/// Round-off of either algorithm: a few hundred operations on numbers of
/// order one, each off by ε ≈ 1.1e-16, amplified by the mass matrix's
/// condition (below 1e3 for the tests' parameters), as in planar_test.
constexpr double aba_round_off = 1e-11;

/// The largest disagreement of either form with Newton–Euler + M, relative
/// to the largest |v̇|, over `states` random states (q, v in ±2) drawn from
/// seed; prepare(q) makes q valid where it must be (a unit quaternion).
template <class S, class Prepare>
double worst_aba_disagreement(const S& s, unsigned seed, int states, Prepare prepare) {
  constexpr int nq = S::n_q, nv = S::n_v;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2);
  double worst = 0;
  for (int k = 0; k < states; ++k) {
    std::array<double, nq> q;
    std::array<double, nv> v, ref, unrolled, shared;
    for (auto& x : q) x = u(rng);
    for (auto& x : v) x = u(rng);
    prepare(q);
    accelerations_newton_euler(s, 0.1, q.data(), v.data(), ref.data());
    accelerations_articulated_body<aba_steps::unrolled>(s, 0.1, q.data(), v.data(), unrolled.data());
    accelerations_articulated_body<aba_steps::shared>(s, 0.1, q.data(), v.data(), shared.data());
    double scale = 1;
    for (const double x : ref) scale = std::max(scale, std::abs(x));
    for (int i = 0; i < nv; ++i)
      worst = std::max({worst, std::abs(unrolled[i] - ref[i]) / scale, std::abs(shared[i] - ref[i]) / scale});
  }
  return worst;
}
template <class S>
double worst_aba_disagreement(const S& s, unsigned seed, int states) {
  return worst_aba_disagreement(s, seed, states, [](auto&) {});
}

}  // namespace flange::test
