// Stepping with a projection after every step: the way a scene with loops
// keeps its constraint errors at round-off (docs/loops.md), and a scene with
// quaternions their norms.
//
//   auto stepper = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<State>());
//   flange::integrate_projected(stepper, fourbar, x, 0.0, 10.0, 1e-3, observer);
//
// After each accepted step, normalize(scene, x) (simulate/system.hpp) moves
// (q, v) back onto Φ(q) = 0 and G·v = 0 by the least change; an FSAL
// stepper (dopri5) is reset so that its stored derivative is not reused for
// the moved state. A scene with neither loops nor quaternions has nothing to
// project (detail::needs_projection): its steps are those of
// odeint::integrate_adaptive, first-same-as-last evaluations kept.
// Controlled steppers step adaptively, simple ones (rk4) with the fixed dt. The system stepped may be the scene or a wrapper around
// it (checked(scene, b)). The observer sees the state at t0 and after each
// step, as with odeint::integrate_adaptive.
#pragma once
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <boost/numeric/odeint/stepper/stepper_categories.hpp>
#include <boost/numeric/odeint/util/unwrap_reference.hpp>
#include <cmath>
#include <functional>
#include <type_traits>

#include "flange/errors.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

namespace detail {
/// What integrate_projected calls around each step (simulate.hpp checks
/// there, once per step): after(prev, t_prev, h, x, t) once a step from
/// (prev, t_prev) of size h is accepted and projected, and
/// collapsing(x, t, h) before it reports a collapsed step size, with the
/// attempt that failed. The default does nothing and keeps no copy.
struct no_step_check {
  static constexpr bool wants_previous = false;
  template <class State>
  void after(const State&, double, double, const State&, double) const {}
  template <class State>
  void collapsing(const State&, double, double) const {}
};

template <class Stepper, class System, class S, class State, class Observer, class StepCheck>
std::size_t integrate_projected_with(Stepper& stepper, System system, const S& scene, State& x, double t0, double t1,
                                     double dt, Observer& observer, const StepCheck& check) {
  namespace odeint = boost::numeric::odeint;
  using category = typename odeint::unwrap_reference<Stepper>::type::stepper_category;
  constexpr bool controlled = std::is_base_of_v<odeint::controlled_stepper_tag, category>;
  static_assert(controlled || std::is_base_of_v<odeint::stepper_tag, category>,
                "flange: integrate_projected takes a simple stepper (runge_kutta4) or a controlled one "
                "(make_controlled); a dense-output stepper cannot be projected between its steps");
  constexpr bool project = needs_projection<S>();
  check_loops(scene, x);
  if constexpr (project) normalize(scene, x);
  double t = t0;
  observer(x, t);
  std::size_t steps = 0;
  State prev{};
  while ((t1 - t) * (t1 - t0) > 0 && std::abs(t1 - t) > 1e-14 * std::abs(t1)) {
    if ((t + dt - t1) * (t1 - t0) > 0) dt = t1 - t;
    const double t_prev = t;
    if constexpr (StepCheck::wants_previous) prev = x;
    double h = dt;
    if constexpr (controlled) {
      int rejected = 0;
      while (stepper.try_step(system, x, t, dt) == odeint::fail) {
        if (++rejected > 500 || std::abs(dt) < 1e-14 * std::max(1.0, std::abs(t))) {
          check.collapsing(x, t, h);
          throw simulation_error(concat("flange: the step size collapsed to ", dt, " at t = ", t, " after ", rejected,
                                        " rejected steps (a tolerance too tight for double precision, or a "
                                        "non-smooth input)"),
                                 t);
        }
        h = dt;
      }
      if constexpr (project && requires { stepper.reset(); }) stepper.reset();
    } else {
      stepper.do_step(system, x, t, dt);
      t += dt;
    }
    if constexpr (project) normalize(scene, x);
    check.after(prev, t_prev, h, x, t);
    ++steps;
    observer(x, t);
  }
  return steps;
}
}  // namespace detail

template <class Stepper, class System, class S, class State, class Observer = boost::numeric::odeint::null_observer>
std::size_t integrate_projected(Stepper stepper, System system, const S& scene, State& x, double t0, double t1,
                                double dt, Observer observer = Observer()) {
  return detail::integrate_projected_with(stepper, std::move(system), scene, x, t0, t1, dt, observer,
                                          detail::no_step_check{});
}

/// The same with the scene itself as the system.
template <class Stepper, class S, class State, class Observer = boost::numeric::odeint::null_observer>
  requires requires { S::n_state; }
std::size_t integrate_projected(Stepper stepper, const S& scene, State& x, double t0, double t1, double dt,
                                Observer observer = Observer()) {
  return integrate_projected(std::move(stepper), std::cref(scene), scene, x, t0, t1, dt, std::move(observer));
}

}  // namespace flange
