// One checked call for a whole run: the path that fails loudly by default.
//
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0);                    // dopri5 at 1e-8
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0, {.tolerance = 1e-12}, observer);
//   auto x1 = flange::simulate<method::rosenbrock4>(stiff, x0, 0.0, 10.0);   // rosenbrock4.hpp
//
// It runs the integration loop (integrate.hpp) with a method's dense-output
// stepper (method.hpp; dopri5 by default): loops closed and quaternions
// normalised after every step (nothing on a scene that has neither), and
// checks once per step, not at every evaluation: the evaluations are
// counted against a budget, and each accepted state must be finite (a NaN
// in any stage reaches the step's result). When one is not, or the step
// size collapses, the step is replayed through checked(scene, budget)
// (checked.hpp), whose first non-finite evaluation names its own time,
// state and reason. So a non-finite state or derivative, a spent budget, a
// singular mass matrix, a loop left open or a step size that collapses each
// throw, with the time, the state and the reason, for a few per cent of a
// step's cost (docs/performance.md). An ensemble's case runs the same loop
// with the same checks, so it ends bit for bit where simulate ends. The raw
// Odeint system (the scene itself) stays for those who want their own
// stepper; it neither checks nor projects.
#pragma once
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <cmath>
#include <limits>

#include "flange/errors.hpp"
#include "flange/simulate/checked.hpp"
#include "flange/simulate/integrate.hpp"
#include "flange/simulate/method.hpp"
#include "flange/simulate/options.hpp"

namespace flange {

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

/// The loop's check in a checked run (simulate, the ensembles): after each
/// step the state must be finite; the replay names the reason.
template <class S, class Stepping>
struct checked_steps {
  const S* scene;
  Stepping fresh;  ///< an unused stepping like the one stepping, for replays
  template <class State>
  void after(const State& prev, double t_prev, const State& x, double t) const {
    if (finite(x)) [[likely]]
      return;
    replay(prev, t_prev, t - t_prev);
    fail_at(concat("the state is not finite after the step from t = ", t_prev, " (", describe(prev), ")"), x, t);
  }
  template <class State>
  void collapsing(const State& x, double t, double h) const {
    replay(x, t, h);
  }
  /// The step from (x, t) of size h under per-evaluation checks: throws at
  /// its first non-finite evaluation.
  template <class State>
  void replay(const State& x, double t, double h) const {
    budget b;
    auto sys = checked(*scene, b);
    Stepping st = fresh;
    st.start(x, t, h, t + h);
    try {
      st.step(sys, t + h);
    } catch (const step_collapse&) {
    }
  }
};

/// A checked run of the loop with a method: what simulate and an ensemble's
/// case both do. Returns the number of steps; evals counts the evaluations.
template <class Method, class S, class State, class Watcher>
long checked_run(const S& scene, State& x, double t0, double t1, const simulate_options& o, long& evals,
                 Watcher& watcher) {
  auto st = method_stepping<Method, State>(scene, o.abs_tol(), o.rel_tol());
  const checked_steps<S, decltype(st)> check{&scene, st};
  counted_system<S> sys{&scene, &evals, o.max_rhs_evals};
  return integrate(st, sys, scene, x, t0, t1, (t1 >= t0 ? 1 : -1) * o.dt, watcher, check);
}
}  // namespace detail

/// The state at t1 from x0 at t0; observer(x, t) sees the start and every
/// step. Method: method::dopri5 (the default), method::bulirsch_stoer,
/// method::rosenbrock4 (simulate/rosenbrock4.hpp) or one's own (method.hpp).
/// Throws simulation_error (time, state, reason) or parameter_error.
template <class Method = method::dopri5, class S, class Observer = boost::numeric::odeint::null_observer>
typename S::state_type simulate(const S& scene, typename S::state_type x0, double t0, double t1,
                                const simulate_options& o = {}, Observer observer = Observer()) {
  detail::check_run("simulate", o, t0, t1);
  long evals = 0;
  detail::observe_steps<Observer> watch{observer};
  detail::checked_run<Method>(scene, x0, t0, t1, o, evals, watch);
  return x0;
}

}  // namespace flange
