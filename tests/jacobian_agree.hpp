// The analytic Jacobian's agreement check, shared by the tests that hold
// scenes to it (jacobian_analytic_test.cpp, jacobian_ball_test.cpp,
// jacobian_ball_trees_test.cpp, jacobian_series_test.cpp), and their trees'
// shapes without force elements.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include <catch2/catch.hpp>

#include <flange/models/tree.hpp>
#include <flange/simulate/jacobian.hpp>

#include "tree_laws.hpp"

namespace flange::test {

/// The shape t without its force elements (no Torque, line force or load on
/// any joint): the trees whose Jacobian is the passes' alone.
constexpr models::tree_shape without_force_elements(models::tree_shape t) {
  for (int i = 0; i < t.n; ++i) {
    t.torque[i] = false;
    t.line[i] = -2;
    t.load[i] = 0;
  }
  return t;
}

/// Both Jacobians (the analytic one whether or not jacobian() takes it for
/// this scene) and ∂f/∂t at state x (number k, for the report). The two
/// differ by the round-off of their solves, a few ε times the largest entry
/// times M's condition: 1e-12 of the largest entry is the bar (measured: 3e-14
/// at most on trees of one-axis joints, 2e-13 on a floating quadruped whose
/// legs turn 5e-4 kg m² against a 10 kg trunk). Central differences too,
/// unless with_finite_differences is false.
template <class S>
void agree_at(const S& scene, const typename S::state_type& x, double t = 0.3, int k = 0,
              bool with_finite_differences = true) {
  static_assert(detail::analytic_derivatives<S>(), "the scene should take the analytic Jacobian");
  {
    Eigen::Matrix<double, S::n_state, 1> ft, ft_dual;
    test::poison_stack();
    const auto J = detail::jacobian_analytic(scene, t, x, &ft);
    test::poison_stack();
    const auto J_dual = jacobian_dual(scene, t, x, &ft_dual);
    const double scale = std::max(1.0, J_dual.cwiseAbs().maxCoeff());
    INFO("state " << k << ", largest entry " << scale);
    CHECK((J - J_dual).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    CHECK((ft - ft_dual).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    CHECK(J.allFinite());
    // v̇ from M's factor in the derivatives' own passes, against the
    // scene's derivative (the articulated-body algorithm or M's LDLᵀ).
    std::array<double, S::n_state> xs, f;
    for (int i = 0; i < S::n_state; ++i) xs[i] = x[i];
    scene(xs, f, t);
    detail::derivative_rows<S> rows;
    std::array<double, S::n_v> vdot;
    REQUIRE(detail::acceleration_derivatives(scene, t, xs.data(), xs.data() + S::n_q, rows, vdot.data()).index < 0);
    // (Their round-off scales with the largest acceleration, as the
    // Jacobians' with their largest entry.)
    double largest = 1;
    for (int i = 0; i < S::n_v; ++i) largest = std::max(largest, std::abs(f[S::n_q + i]));
    for (int i = 0; i < S::n_v; ++i) CHECK(std::abs(vdot[i] - f[S::n_q + i]) <= 1e-12 * largest);
#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
    // The passes compiled for AVX2 give the portable passes' numbers to the
    // bit (no product and sum fused into one rounding).
    if (detail::cpu_has_avx2) {
      constexpr bool A = detail::articulated_solve<S>();
      detail::derivative_rows<S> portable, avx2;
      std::array<double, S::n_v> vdot_portable, vdot_avx2;
      const double* q = xs.data();
      detail::acceleration_derivatives_portable<S, A>(scene, t, q, q + S::n_q, portable, vdot_portable.data());
      detail::acceleration_derivatives_avx2<S, A>(scene, t, q, q + S::n_q, avx2, vdot_avx2.data());
      CHECK(std::memcmp(portable.data(), avx2.data(), sizeof(double) * portable.size()) == 0);
      CHECK(std::memcmp(vdot_portable.data(), vdot_avx2.data(), sizeof vdot_portable) == 0);
    }
#endif
    // And central differences to their accuracy (h = ε^(1/3): about 1e-10
    // relative, so 1e-7 of the largest entry; jacobian_test.cpp's bar), where
    // the derivative is smooth on the scale of h.
    if (!with_finite_differences) return;
    Eigen::Matrix<double, S::n_state, 1> ft_fd;
    const auto J_fd = jacobian_finite_difference(scene, t, x, &ft_fd);
    CHECK((J - J_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
    CHECK((ft - ft_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  }
}

/// agree_at three random states.
template <class S>
void agree(const S& scene, std::mt19937& rng, double t = 0.3) {
  for (int k = 0; k < 3; ++k) agree_at(scene, test::random_state(scene, rng), t, k);
}

}  // namespace flange::test
