// The exact Jacobian ∂f/∂x of a scene's derivative, by forward-mode dual
// numbers through the scalar-templated dynamics (used by rosenbrock4.hpp).
//
// jacobian_finite_difference is the usual stand-in, central differences, for
// comparison: 2·(n + 1) derivative evaluations and about 1e-10 relative
// error, against one dual-number evaluation carrying n + 1 directions.
//
// Inputs take part when they are generic in their scalar (a lambda of
// (auto t) or (auto t, const auto& x)); an input written for double is
// evaluated at the time's value and counts as constant in x.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "flange/math/dual.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

template <class S>
using jacobian_matrix = Eigen::Matrix<double, S::n_state, S::n_state>;

/// ∂f/∂x at (t, x), and ∂f/∂t into *dfdt when given.
template <class S, class State>
jacobian_matrix<S> jacobian(const S& scene, double t, const State& x, Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  S::require_state_size(x);
  constexpr int n = S::n_state;
  using D = dual<double, n + 1>;  // directions: the n states, then t
  std::array<D, n> xd, fd;
  for (int i = 0; i < n; ++i) xd[i] = D::variable(x[i], i);
  const D td = D::variable(t, n);
  scene(xd, fd, td);
  jacobian_matrix<S> J;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) J(i, k) = fd[i].d[k];
    if (dfdt) (*dfdt)(i) = fd[i].d[n];
  }
  return J;
}

/// ∂f/∂x (and ∂f/∂t into *dfdt) by central differences, step
/// h = ε^(1/3)·max(1, |x_k|), which balances truncation (h²) against rounding
/// (ε/h): about 1e-10 relative error.
template <class S, class State>
jacobian_matrix<S> jacobian_finite_difference(const S& scene, double t, const State& x,
                                              Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  S::require_state_size(x);
  constexpr int n = S::n_state;
  const double cbrt_eps = std::cbrt(std::numeric_limits<double>::epsilon());
  jacobian_matrix<S> J;
  std::array<double, n> xp, xm, fp, fm;
  for (int k = 0; k <= n; ++k) {
    if (k == n && !dfdt) break;
    std::copy_n(x.begin(), n, xp.begin());
    std::copy_n(x.begin(), n, xm.begin());
    double tp = t, tm = t;
    const double h = cbrt_eps * std::max(1.0, std::abs(k < n ? double(x[k]) : t));
    if (k < n) {
      xp[k] += h;
      xm[k] -= h;
    } else {
      tp += h;
      tm -= h;
    }
    scene(xp, fp, tp);
    scene(xm, fm, tm);
    for (int i = 0; i < n; ++i) {
      const double v = (fp[i] - fm[i]) / (2 * h);
      if (k < n) J(i, k) = v;
      else (*dfdt)(i) = v;
    }
  }
  return J;
}

}  // namespace flange
