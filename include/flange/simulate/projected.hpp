// Stepping a scene with a stepper of one's choice, projected after every
// step: the way a scene with loops keeps its constraint errors at round-off
// (docs/loops.md), and a scene with quaternions their norms.
//
//   auto stepper = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<State>());
//   flange::integrate_projected(stepper, fourbar, x, 0.0, 10.0, 1e-3, observer);
//
// It is the integration loop (integrate.hpp) with the stepper given: simple
// steppers (runge_kutta4) step with the fixed dt, controlled ones
// (make_controlled) adaptively from dt, dense-output ones
// (make_dense_output) adaptively with whole steps. After each accepted step
// the state is moved back onto Φ(q) = 0 and G·v = 0 and quaternions to unit
// norm (a loop that cannot be closed again throws simulation_error), and a
// first-same-as-last stepper (dopri5) is restarted so that it does not reuse
// a derivative of the unprojected state. A scene with neither loops nor
// quaternions is not touched: its steps are those of
// odeint::integrate_adaptive, first-same-as-last evaluations kept. The
// system stepped may be the scene or a wrapper around it (checked(scene,
// b)). The observer sees the state at t0 and after each step. Returns the
// number of steps.
#pragma once
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <cstddef>
#include <functional>

#include "flange/simulate/integrate.hpp"

namespace flange {

template <class Stepper, class System, class S, class State, class Observer = boost::numeric::odeint::null_observer>
std::size_t integrate_projected(Stepper stepper, System system, const S& scene, State& x, double t0, double t1,
                                double dt, Observer observer = Observer()) {
  auto st = detail::stepping_for<Stepper, State>(std::move(stepper));
  detail::observe_steps<Observer> watch{observer};
  return static_cast<std::size_t>(
      detail::integrate(st, system, scene, x, t0, t1, dt, watch, detail::no_step_check{}));
}

/// The same with the scene itself as the system.
template <class Stepper, class S, class State, class Observer = boost::numeric::odeint::null_observer>
  requires requires { S::n_state; }
std::size_t integrate_projected(Stepper stepper, const S& scene, State& x, double t0, double t1, double dt,
                                Observer observer = Observer()) {
  return integrate_projected(std::move(stepper), std::cref(scene), scene, x, t0, t1, dt, std::move(observer));
}

}  // namespace flange
