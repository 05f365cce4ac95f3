// An equilibrium of a scene: a state x with ẋ = f(t, x) = 0 (at rest, every
// force balanced), found by Newton's method from a guess, for linearize
// (linearize.hpp) and the stability of a pose.
//
//   auto x0 = equilibrium(scene, 0.0, guess);        // throws flange::error if none is found
//
// Each step is the least change δ with J·δ = −f (J the exact Jacobian,
// jacobian.hpp), so that where equilibria form a family (a cart anywhere on
// its rail) it moves to the nearest one, halved until max |ẋ| decreases,
// then projected back onto the loops' constraints and unit quaternions
// (normalize). It stops at max |ẋ| ≤ tolerance, or throws naming the
// entry of ẋ that stays largest, its joint, and the state.
#pragma once
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include <Eigen/Dense>

#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/loops.hpp"
#include "flange/errors.hpp"
#include "flange/simulate/jacobian.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

struct equilibrium_options {
  double tolerance = 1e-10;  ///< on max |ẋ_i|, in the state's units per second (rad/s, m/s, rad/s², m/s²)
  int max_iterations = 50;   ///< Newton steps
};

namespace detail {
/// Entry i of ẋ in words: "q̇[i], joint "j"'s coordinate k's rate" or
/// "v̇[i], joint "j"'s rate k's derivative".
template <class S>
std::string state_entry_name(int i) {
  if (i >= S::n_q) {
    const auto [joint, k] = rate_owner<S>(i - S::n_q);
    return concat("v̇[", i - S::n_q, "], joint \"", joint, "\"'s rate ", k, "'s derivative");
  }
  for (int c = 0; c < S::n_components; ++c)
    if (S::tree.q_offset[c] >= 0 && i >= S::tree.q_offset[c] && i < S::tree.q_offset[c] + S::table.nq[c])
      return concat("q̇[", i, "], joint \"", S::table.names[c], "\"'s coordinate ", i - S::tree.q_offset[c], "'s rate");
  return concat("ẋ[", i, "]");
}

/// The least δ with J·δ = f (x − δ the Newton step). With loops the step
/// stays on them to first order: δq and δv both in G(q)'s null space (q̇ = v,
/// so G is Φ's Jacobian in q), where Newton in all of x would also move off
/// the loops and the projection after it pull back, and the two stall.
template <class S, class State, class Vec>
Vec equilibrium_step(const S& scene, double t, const State& x, const Vec& f) {
  constexpr int n = S::n_state;
  const auto J = jacobian(scene, t, x);
  if constexpr (has_loops<S> && S::n_q == S::n_v) {
    std::array<double, S::n_v> zero{};
    Eigen::FullPivLU<Eigen::Matrix<double, n_constraints<S>(), S::n_v>> lu(
        loop_kinematics<S>(scene, x.data(), zero.data()).G);
    lu.setThreshold(1e-10);
    const Eigen::MatrixXd T = lu.kernel();
    const auto k = T.cols();
    Eigen::MatrixXd Tx = Eigen::MatrixXd::Zero(n, 2 * k);
    Tx.topLeftCorner(S::n_q, k) = T;
    Tx.bottomRightCorner(S::n_v, k) = T;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J * Tx);
    cod.setThreshold(1e-10);
    return Tx * cod.solve(f);
  } else {
    Eigen::CompleteOrthogonalDecomposition<jacobian_matrix<S>> cod(J);
    cod.setThreshold(1e-10);
    return cod.solve(f);
  }
}
}  // namespace detail

/// A state near `guess` with max |ẋ| ≤ o.tolerance at time t.
template <class S, class State>
typename S::state_type equilibrium(const S& scene, double t, const State& guess, equilibrium_options o = {}) {
  S::require_state_size(guess);
  if (!(o.tolerance > 0) || o.max_iterations < 1)
    throw parameter_error(detail::concat("flange: equilibrium: the tolerance must be positive and max_iterations at "
                                         "least 1 (given ", o.tolerance, " and ", o.max_iterations, ")"));
  constexpr int n = S::n_state;
  using vec = Eigen::Matrix<double, n, 1>;
  typename S::state_type x;
  for (int i = 0; i < n; ++i) x[i] = guess[i];
  normalize(scene, x);
  auto rate = [&](const typename S::state_type& y, vec& f) {
    typename S::state_type d;
    scene(y, d, t);
    for (int i = 0; i < n; ++i) f[i] = d[i];
    return f.cwiseAbs().maxCoeff();  // NaN if any entry is
  };
  vec f;
  double r = rate(x, f);
  auto fail = [&](std::string_view why) {
    Eigen::Index worst = 0;
    f.cwiseAbs().maxCoeff(&worst);
    throw error(detail::concat("flange: equilibrium: no state with ẋ = 0 found near the guess at t = ", t, ": ", why,
                               "; max |ẋ| = ", r, " (tolerance ", o.tolerance, ") at ",
                               detail::state_entry_name<S>(int(worst)), ", ",
                               detail::describe_state(x.data(), S::n_q, x.data() + S::n_q, S::n_v),
                               ". A scene driven by a force that nothing balances (a constant torque on a free "
                               "wheel) has no equilibrium; otherwise start closer to one"));
  };
  if (!std::isfinite(r)) fail("the derivative is not finite at the guess");
  for (int it = 0; it < o.max_iterations && r > o.tolerance; ++it) {
    const vec step = detail::equilibrium_step(scene, t, x, f);
    bool better = false;
    for (double lambda = 1; lambda > 1e-6 && !better; lambda /= 2) {
      typename S::state_type y;
      for (int i = 0; i < n; ++i) y[i] = x[i] - lambda * step[i];
      normalize(scene, y);
      vec fy;
      const double ry = rate(y, fy);
      if (ry < r) {
        x = y;
        f = fy;
        r = ry;
        better = true;
      }
    }
    if (!better) fail("Newton's steps no longer decrease |ẋ| (a minimum of |ẋ| that is not an equilibrium)");
  }
  if (!(r <= o.tolerance))
    fail(detail::concat("the ", o.max_iterations, " Newton steps allowed (max_iterations) are spent"));
  return x;
}

}  // namespace flange
