// The linearisation of a scene's motion at a state:
//
//   ẋ ≈ f(t, x*) + A·(x − x*) + B·u,   A = ∂f/∂x,   B = ∂f/∂u,
//
// with u the generalized forces added at the joints named (a Revolute's
// torque about its axis, a Prismatic's force along it, one per rate of a
// multi-axis joint): the inputs of a drive. For LQR, MPC and stability
// studies (examples/lqr_balance.cpp, docs/control.md).
//
//   const auto lin = linearize<"cart">(scene, t, x);   // lin.A: 4 × 4, lin.B: 4 × 1
//
// A is the exact Jacobian (jacobian.hpp). B's rows for q̇ are zero; its rows
// for v̇ are the accelerations a unit force at each input gives, v̇ being
// affine in the joints' forces: M⁻¹ on a tree, and with loops the
// constrained response w of [M Gᵀ; G 0]·(w, −λ) = (e, 0), solved densely
// (an analysis call, not the derivative's path).
#pragma once
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/loops.hpp"
#include "flange/errors.hpp"
#include "flange/simulate/jacobian.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

/// A and B of ẋ ≈ f(t, x*) + A·(x − x*) + B·u; `inputs` names u's entries
/// (a joint's name, with its rate's index for a multi-axis joint).
template <class S, int NU>
struct linearization {
  jacobian_matrix<S> A = make_jacobian_matrix<S>();
  Eigen::Matrix<double, S::n_state, NU> B;
  std::array<std::string, NU> inputs;
};

namespace detail {
/// The number of inputs: the rates of the joints named.
template <class S, fixed_string... Joints>
constexpr int n_inputs() {
  return (0 + ... + S::template component_type<named_joint<S, Joints>::index>::nv);
}

/// ∂v̇/∂τ: the accelerations a unit generalized force at each rate gives, at
/// (q, v). On a tree M⁻¹; with loops the constrained response. Throws where
/// the accelerations do not depend on the forces uniquely (a singular M).
template <class S>
Eigen::Matrix<double, S::n_v, S::n_v> force_response(const S& scene, double t, const double* q, const double* v) {
  constexpr int nv = S::n_v, m = n_constraints<S>(), nk = nv + m;
  Eigen::Matrix<double, nk, nk> K = Eigen::Matrix<double, nk, nk>::Zero();
  K.template topLeftCorner<nv, nv>() = mass_matrix(scene, q);
  if constexpr (m > 0) {
    const auto k = loop_kinematics<S>(scene, q, v);
    K.template topRightCorner<nv, m>() = k.G.transpose();
    K.template bottomLeftCorner<m, nv>() = k.G;
  }
  Eigen::Matrix<double, nk, nv> rhs = Eigen::Matrix<double, nk, nv>::Zero();
  rhs.template topRows<nv>().setIdentity();
  // Rows of G that repeat others (redundant constraints) leave K singular
  // while w stays unique: the minimum-norm solution, then a check that it
  // solves the system (it does not where M is singular on the motions the
  // loops allow).
  Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, nk, nk>> cod(K);
  cod.setThreshold(1e-12);
  const Eigen::Matrix<double, nk, nv> w = cod.solve(rhs);
  const double miss = (K * w - rhs).cwiseAbs().maxCoeff(),
               scale = 1 + K.cwiseAbs().maxCoeff() * w.cwiseAbs().maxCoeff();
  if (!(miss <= 1e-9 * scale))
    throw simulation_error(concat("flange: linearize: the accelerations do not follow from the joints' forces at t = ",
                                  t, ", ", describe_state(q, S::n_q, v, S::n_v),
                                  ": the mass matrix is singular on the motions the scene allows (a body without mass "
                                  "or inertia where a joint moves it)"),
                           t, state_values(q, S::n_q, v, S::n_v), "singular mass matrix");
  return w.template topRows<nv>();
}
}  // namespace detail

/// The linearisation at (t, x) with u the generalized forces at the joints
/// named (in the order named; each joint's rates in order). A misspelt
/// name, or a joint a loop cut (its force acts through the loop's
/// constraint), is a compile-time error naming the joints there are.
template <fixed_string... Joints, class S, class State>
linearization<S, detail::n_inputs<S, Joints...>()> linearize(const S& scene, double t, const State& x) {
  S::require_state_size(x);
  constexpr int NU = detail::n_inputs<S, Joints...>();
  linearization<S, NU> r;
  jacobian(scene, t, x, r.A);
  r.B.setZero();
  if constexpr (NU > 0) {
    const double* xs = &x[0];
    const auto W = detail::force_response(scene, t, xs, xs + S::n_q);
    int col = 0;
    auto add = [&]<fixed_string Name>() {
      using J = detail::named_joint<S, Name>;
      constexpr int nv = S::template component_type<J::index>::nv, v0 = S::tree.v_offset[J::index];
      for (int k = 0; k < nv; ++k, ++col) {
        r.B.col(col).template tail<S::n_v>() = W.col(v0 + k);
        r.inputs[col] = nv == 1 ? std::string(Name.view()) : detail::concat(Name.view(), "[", k, "]");
      }
    };
    (add.template operator()<Joints>(), ...);
  }
  return r;
}

}  // namespace flange
