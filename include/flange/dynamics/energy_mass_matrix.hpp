// The mass matrix read off the kinetic energy: T = ½·vᵀ·M(q)·v, so column j
// of M is ∂T/∂v at v = e_j, which dual numbers (math/dual.hpp) carry exactly
// through energy() (dynamics/energy.hpp: the pose pass and the bodies'
// velocities, no dynamics). It costs n_v·⌈n_v/4⌉ of those: a check, not a
// fast path. It shares no code with the composite-rigid-body pass the
// derivative uses (dynamics/mass_matrix.hpp), so the tests and the fuzz
// target use it as a second algorithm, and to judge how well conditioned a
// state is before they compare two algorithms there.
//
//   const auto M = flange::energy_mass_matrix(scene, x);   // Eigen, n_v × n_v
//   const double c = flange::mass_matrix_condition(scene, x);
#pragma once
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <array>
#include <limits>

#include "flange/dynamics/energy.hpp"
#include "flange/math/dual.hpp"

namespace flange {

/// M(q) at the coordinates of state x (its rates are not used). The
/// derivatives are taken K = 4 directions at a time (dual<double, 4>), so an
/// evaluation's variables stay a few kB whatever the scene's size.
template <class S, class State>
Eigen::Matrix<double, S::n_v, S::n_v> energy_mass_matrix(const S& scene, const State& x) {
  constexpr int NQ = S::n_q, NV = S::n_v, K = NV < 4 ? NV : 4;
  using D = dual<double, K>;
  Eigen::Matrix<double, NV, NV> M;
  for (int j = 0; j < NV; ++j)
    for (int i0 = 0; i0 < NV; i0 += K) {
      std::array<D, S::n_state> xd;
      for (int i = 0; i < NQ; ++i) xd[i] = D(static_cast<double>(x[i]));
      for (int i = 0; i < NV; ++i) xd[NQ + i] = D(i == j ? 1.0 : 0.0);
      for (int k = 0; k < K && i0 + k < NV; ++k) xd[NQ + i0 + k].d[k] = 1;  // ∂/∂v_(i0+k)
      const auto e = energy(scene, D(0.0), xd);
      for (int k = 0; k < K && i0 + k < NV; ++k) M(i0 + k, j) = e.kinetic.d[k];
    }
  return M;
}

/// The condition number of M(q), the ratio of its largest to its smallest
/// eigenvalue (infinity when M is singular). The eigenvalues are taken of a
/// dynamic-size copy of M: the eigen-solver is then compiled once for every
/// scene size in a program, where a fixed-size one was compiled again for
/// each (12 of the 66 s a test unit with many scene sizes took to compile,
/// docs/performance.md). It allocates; it is a check, not a fast path.
template <class S, class State>
double mass_matrix_condition(const S& scene, const State& x) {
  const Eigen::MatrixXd M = energy_mass_matrix(scene, x);
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues();
  return ev[0] > 0 ? ev[S::n_v - 1] / ev[0] : std::numeric_limits<double>::infinity();
}

}  // namespace flange
