// One checked call for a whole run: the path that fails loudly by default.
//
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0);                    // dopri5 at 1e-8
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0, {.tolerance = 1e-12}, observer);
//
// It steps a controlled dopri5 with a projection after every step
// (integrate_projected, projected.hpp: loops closed, quaternions normalised;
// nothing on a scene that has neither), and checks once per step, not at
// every evaluation: the evaluations are counted against a budget, and each
// accepted state must be finite (a NaN in any stage reaches the step's
// result). When one is not, or the step size collapses, the step is replayed
// through checked(scene, budget) (checked.hpp), whose first non-finite
// evaluation names its own time, state and reason. So a non-finite state or
// derivative, a spent budget, a singular mass matrix, a loop left open or a
// step size that collapses each throw, with the time, the state and the
// reason, for a few per cent of a step's cost (docs/performance.md). The raw
// Odeint system (the scene itself) stays for those who want their own
// stepper; it checks nothing.
#pragma once
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <limits>

#include "flange/errors.hpp"
#include "flange/simulate/checked.hpp"
#include "flange/simulate/projected.hpp"

namespace flange {

struct simulate_options {
  double tolerance = 1e-8;  ///< dopri5's absolute and relative tolerance
  double dt = 1e-3;         ///< the first step's size
  long max_rhs_evals = 100'000'000;
};

namespace detail {
/// The scene with its evaluations counted against a budget.
template <class S>
struct counted_system {
  const S* scene;
  long* evals;
  long max_evals;
  template <class State, class T>
  void operator()(const State& x, State& dxdt, const T t) const {
    if (++*evals > max_evals) [[unlikely]]
      fail_at(budget_spent(max_evals), x, t);
    (*scene)(x, dxdt, t);
  }
};

/// simulate's check after each step, and the replay that names the reason.
template <class S, class Stepper>
struct checked_steps {
  static constexpr bool wants_previous = true;
  const S* scene;
  Stepper fresh;  ///< an unused stepper like the one stepping, for replays
  template <class State>
  void after(const State& prev, double t_prev, double h, const State& x, double t) const {
    if (finite(x)) [[likely]]
      return;
    replay(prev, t_prev, h);
    fail_at(concat("the state is not finite after the step from t = ", t_prev, " (", describe(prev), ")"), x, t);
  }
  template <class State>
  void collapsing(const State& x, double t, double h) const {
    replay(x, t, h);  // a non-finite stage is the true reason, if there is one
  }
  /// The step from (x, t) of size h under per-evaluation checks: throws at
  /// its first non-finite evaluation.
  template <class State>
  void replay(const State& x, double t, double h) const {
    budget b;
    Stepper st = fresh;
    State y = x;
    st.try_step(checked(*scene, b), y, t, h);
  }
};
}  // namespace detail

/// The state at t1 from x0 at t0; observer(x, t) sees the start and every
/// step. Throws simulation_error (time, state, reason) or parameter_error.
template <class S, class Observer = boost::numeric::odeint::null_observer>
typename S::state_type simulate(const S& scene, typename S::state_type x0, double t0, double t1,
                                const simulate_options& o = {}, Observer observer = Observer()) {
  namespace odeint = boost::numeric::odeint;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  if (!(o.tolerance >= 10 * eps))
    throw parameter_error(detail::concat("flange: simulate: tolerance ", o.tolerance,
                                         " cannot be met in double precision (round-off alone is ", eps,
                                         " per step); use 1e-14 or more"));
  if (!(std::isfinite(t0) && std::isfinite(t1)))
    throw parameter_error(detail::concat("flange: simulate: the times t0 = ", t0, " and t1 = ", t1, " must be finite"));
  if (!(o.dt > 0))
    throw parameter_error(detail::concat("flange: simulate: the first step dt = ", o.dt, " must be positive"));
  if (!detail::finite(x0))
    throw simulation_error(
        detail::concat("flange: the state is not finite at t = ", t0, " (the initial state), ", detail::describe(x0)),
        t0);
  check_coordinates(scene, x0);
  auto stepper = odeint::make_controlled(o.tolerance, o.tolerance, odeint::runge_kutta_dopri5<typename S::state_type>());
  long evals = 0;
  const detail::checked_steps<S, decltype(stepper)> check{&scene, stepper};
  detail::integrate_projected_with(stepper, detail::counted_system<S>{&scene, &evals, o.max_rhs_evals}, scene, x0, t0,
                                   t1, (t1 > t0 ? 1 : -1) * o.dt, observer, check);
  return x0;
}

}  // namespace flange
