// The exact Jacobian ∂f/∂x of a scene's derivative, by forward-mode dual
// numbers through the scalar-templated dynamics (used by rosenbrock4.hpp).
//
// Inputs take part when they are generic in their scalar (a lambda of
// (auto t) or (auto t, const auto& x)); an input written for double is
// evaluated at the time's value and counts as constant in x.
#pragma once
#include "flange/dynamics/newton_euler.hpp"
#include "flange/math/dual.hpp"

namespace flange {

template <class S>
using jacobian_matrix = Eigen::Matrix<double, S::n_state, S::n_state>;

/// ∂f/∂x at (t, x), and ∂f/∂t into *dfdt when given.
template <class S, class State>
jacobian_matrix<S> jacobian(const S& scene, double t, const State& x, Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
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

}  // namespace flange
