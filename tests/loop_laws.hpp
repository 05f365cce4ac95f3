// Laws every loop scene must obey, checked at random closed states:
//   * the accelerations equal a second algorithm's: the constrained
//     equations M·v̇ + b = τ + Gᵀ·λ, G·v̇ = −Ġ·v solved as one dense system
//     [M Gᵀ; G 0] by Eigen's complete orthogonal decomposition (the
//     minimum-norm solution: v̇ is unique where rows repeat others, λ is not),
//     from the public mass matrix and inverse dynamics, sharing no code with
//     the QR of the derivative's solve;
//   * the loops' accelerations are met: G·v̇ = −Ġ·v;
//   * the power balance (tree_laws.hpp): the constraint forces do no work,
//     so d(kinetic + gravity potential)/dt is the power of the force
//     elements and of the joints' own forces — a solve that lost energy
//     silently (a redundant row taken as independent) fails it;
//   * the residual of the components' equations vanishes on the recovered
//     variables.
// Positions where the constraints are near singular (a row within 10 % of
// depending on the others or of vanishing, where the derivative's solve
// damps by design, docs/loops.md) are skipped and counted; rows that repeat
// others exactly (redundant constraints) are not near singular.
#pragma once
#include <Eigen/Dense>
#include <random>

#include <flange/dynamics/forward_dynamics.hpp>
#include <flange/dynamics/loop_solve.hpp>
#include <flange/simulate/simulate.hpp>

#include "tree_laws.hpp"

namespace flange::test {

struct loop_law_errors {
  double algorithms = 0;    ///< max |v̇ − v̇_KKT| / max(1, |v̇|)
  double accelerations = 0; ///< max |G·v̇ + Ġ·v| / max(1, Σ|G_ij·v̇_j|)
  double power = 0;         ///< as tree_laws.hpp's
  double residual = 0;      ///< max scaled residual
  int checked = 0;          ///< closed states checked
  int near_singular = 0;    ///< closed states skipped as near a singular position
};

/// How far the rows are from a singular position, as the derivative's
/// solve measures it (loop_solve.hpp): the smallest singular value of
/// B = L⁻¹·Gᵀ (M = L·Lᵀ) with each column scaled to unit norm (masses and
/// units aside), above 1e-9 (rows that repeat others leave singular values
/// at the closed state's round-off), and each row's norm in G (rows in
/// comparable units, row_units) against the largest (a row that vanishes
/// as a parallelogram lines up; a row of zeros, such as the out-of-plane
/// rows of a planar loop written with run-time axes, is left out). The
/// smaller of the two.
template <class S>
double constraint_independence(const S& s, const Eigen::MatrixXd& M, const Eigen::MatrixXd& G) {
  Eigen::LLT<Eigen::MatrixXd> llt(M);
  Eigen::MatrixXd B = llt.matrixL().solve(G.transpose());  // B = L⁻¹·Gᵀ
  for (int c = 0; c < B.cols(); ++c)
    if (B.col(c).norm() > 0) B.col(c).normalize();
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(B).singularValues();
  double smallest = 1;
  for (int i = 0; i < sv.size(); ++i)
    if (sv[i] > 1e-9) smallest = std::min(smallest, sv[i]);
  const auto units = detail::row_units(s);
  double largest = 0;
  for (int r = 0; r < G.rows(); ++r) largest = std::max(largest, units[r] * G.row(r).norm());
  for (int r = 0; r < G.rows(); ++r)
    if (const double g = units[r] * G.row(r).norm() / largest; g > 1e-9)  // a row of zeros constrains nothing
      smallest = std::min(smallest, g);
  return smallest;
}

/// The laws at one closed state x (or a count of it as near singular).
template <class S>
void check_loop_laws_at(const S& s, const typename S::state_type& x, double t, loop_law_errors& e) {
  constexpr int N = S::n_q, NV = S::n_v, m = detail::n_constraints<S>();
  const double* q = x.data();
  const double* v = x.data() + N;
  const auto k = detail::loop_kinematics<S>(s, q, v);
  const Eigen::MatrixXd M = mass_matrix(s, q), G = k.G;
  if (constraint_independence(s, M, G) < 0.1) {
    ++e.near_singular;
    return;
  }
  typename S::state_type dx;
  poison_stack();
  s(x, dx, t);
  // The second algorithm: [M Gᵀ; G 0]·(v̇, −λ) = (τ − b, −Ġ·v).
  std::array<double, NV> zero{}, tau{};
  const auto b = inverse_dynamics(s, t, q, v, zero.data());
  if constexpr (detail::has_joint_forces<S>()) detail::joint_forces(s, t, state_view<S>(q, v), tau.data());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(NV + m, NV + m);
  K.topLeftCorner(NV, NV) = M;
  K.topRightCorner(NV, m) = G.transpose();
  K.bottomLeftCorner(m, NV) = G;
  Eigen::VectorXd rhs(NV + m);
  for (int i = 0; i < NV; ++i) rhs[i] = tau[i] - b[i];
  for (int i = 0; i < m; ++i) rhs[NV + i] = -k.bias[i];
  const Eigen::VectorXd ref = K.completeOrthogonalDecomposition().solve(rhs);
  double scale = 1;
  for (int i = 0; i < NV; ++i) scale = std::max(scale, std::abs(dx[N + i]));
  for (int i = 0; i < NV; ++i) e.algorithms = std::max(e.algorithms, std::abs(ref[i] - dx[N + i]) / scale);
  for (int r = 0; r < m; ++r) {
    double gv = k.bias[r], sum = 1;
    for (int j = 0; j < NV; ++j) {
      gv += G(r, j) * dx[N + j];
      sum += std::abs(G(r, j) * dx[N + j]);
    }
    e.accelerations = std::max(e.accelerations, std::abs(gv) / sum);
  }
  const auto [gap, pscale] = power_balance(s, t, x);
  e.power = std::max(e.power, std::abs(gap) / pscale);
  poison_stack();
  e.residual = std::max(e.residual, scaled_residual(s, recover(s, t, x)));
  ++e.checked;
}

/// The laws at random closed states: random coordinates and rates
/// (random_state) closed by close_loops, those it cannot close skipped.
template <class S>
void check_loop_laws(const S& s, std::mt19937& rng, loop_law_errors& e, int samples = 10) {
  const int until = e.checked + samples;
  for (int tries = 0; e.checked < until && tries < 50 * samples; ++tries) {
    auto x = random_state(s, rng);
    try {
      close_loops<>(s, x);
    } catch (const parameter_error&) {
      continue;  // no closed position near this guess, or only one turned over
    }
    check_loop_laws_at(s, x, uniform(rng, 0, 1), e);
  }
}

/// The laws at the states of a run from x0 over [0, t1], at `samples` times
/// (for a mechanism whose random closed states crowd at its singular positions).
template <class S>
void check_loop_laws_along(const S& s, const typename S::state_type& x0, double t1, loop_law_errors& e,
                           int samples = 10) {
  const auto tr = simulate(s, x0, output_times(0.0, t1, t1 / samples), {.tolerance = 1e-10});
  for (std::size_t i = 1; i < tr.size(); ++i) check_loop_laws_at(s, tr.x[i], tr.t[i], e);
}

}  // namespace flange::test
