// The Boost.Odeint boundary.
//
// A scene is itself an Odeint system: scene(x, dxdt, t). Its state x = (q, v)
// may be
//   * Scene::state_type = std::array<double, 2n>, with Odeint's default
//     range_algebra (the faster choice for small states), or
//   * an Eigen fixed-size vector, with vector_space_algebra (this header
//     brings Odeint's Eigen support in).
// Every explicit stepper works: runge_kutta4, cash_karp54, dopri5 (controlled
// and dense output), fehlberg78, bulirsch_stoer, adams_bashforth_moulton.
// This header brings those a scene is usually run with (euler, runge_kutta4,
// cash_karp54, dopri5, fehlberg78, bulirsch_stoer; make_controlled,
// make_dense_output; the integrate_* functions), not all of Odeint: for the
// others include <boost/numeric/odeint.hpp> (0.7 s more compile time).
// Symplectic steppers assume a separable Hamiltonian H = T(p) + V(q); a
// configuration-dependent mass matrix breaks that, so they apply only to
// scenes whose mass matrix is constant (e.g. a single revolute joint).
//
// record(scene, f) makes an observer that hands f the recovered solution (all
// DAE variables, cut forces, energy) at every observed time.
#pragma once
#include "flange/detail/odeint_warnings.hpp"
FLANGE_ODEINT_INCLUDES_BEGIN
#include <boost/numeric/odeint/integrate/integrate.hpp>
#include <boost/numeric/odeint/integrate/integrate_adaptive.hpp>
#include <boost/numeric/odeint/integrate/integrate_const.hpp>
#include <boost/numeric/odeint/integrate/integrate_n_steps.hpp>
#include <boost/numeric/odeint/integrate/integrate_times.hpp>
#include <boost/numeric/odeint/stepper/bulirsch_stoer.hpp>
#include <boost/numeric/odeint/stepper/euler.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_cash_karp54.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>
// Odeint's Eigen support needs the core before it.
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
FLANGE_ODEINT_INCLUDES_END

#include "flange/dynamics/recover.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

namespace odeint = boost::numeric::odeint;

/// The state as an Eigen fixed-size vector.
template <class S, class T = double>
using eigen_state = Eigen::Matrix<T, S::n_state, 1>;

/// An Odeint observer calling f(dae_solution) at each observed (x, t).
template <class S, class F>
auto record(const S& scene, F f) {
  return [&scene, f](const auto& x, double t) mutable { f(recover(scene, t, x)); };
}

}  // namespace flange
