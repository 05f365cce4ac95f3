// The integration loop: the one loop behind simulate, integrate_projected,
// integrate_rosenbrock4 and every ensemble case.
//
// From (x, t0) to t1 it takes accepted steps with a stepper (stepping.hpp)
// and, after each,
//   1. asks its check whether the step is sound (simulate's: the state is
//      finite, else the step is replayed under per-evaluation checks to
//      name the true reason),
//   2. moves the state back onto the scene's invariants where the scene has
//      any (restore_invariants: the loops closed at position and velocity
//      level, quaternions at unit norm) and restarts the stepper from there;
//      a scene with neither is not touched, and a first-same-as-last stepper
//      keeps its derivative,
//   3. hands the step to its watcher: an observer, an ensemble's recorders,
//      samples at requested times (through the stepper's interpolation,
//      projected like the steps' ends).
// A step size that collapses, a state that leaves its loops beyond repair,
// a non-finite start and a Contact whose shapes overlap too deeply
// (contact_check.hpp) throw simulation_error with the time, the state and
// the reason. A new way to integrate is a stepping adapter or a watcher, not
// a copy of this loop.
#pragma once
#include <cmath>
#include <limits>
#include <type_traits>

#include "flange/errors.hpp"
#include "flange/simulate/checked.hpp"
#include "flange/simulate/contact_check.hpp"
#include "flange/simulate/stepping.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

namespace detail {

/// Moves x back onto the scene's invariants (normalize's projection) and
/// judges the result: a loop that cannot be closed again (Newton stalls
/// above the closure tolerance, at position or velocity level) throws
/// simulation_error at t, naming the loop.
template <class S, class State>
void restore_invariants(const S& scene, State& x, double t) {
  const closure r = project_state(scene, x);
  if constexpr (has_loops<S>) {
    const double tol = closure_tolerance(scene);
    if (!(r.phi <= tol) || !(r.phid <= tol)) [[unlikely]]
      fail_at(concat(describe_loop(scene, r.worst_row), " could not be closed again: ",
                     r.phi <= tol ? concat("G·v = ", r.phid, " is left after the rates' projection")
                                  : concat("its frames stay ", loop_gap<S>(r.worst_row, r.phi), " after ",
                                           r.iterations, " Newton steps"),
                     " (the step crossed a position where the mechanism locks or branches, or went too far "
                     "off to come back; a tighter tolerance takes smaller steps)"),
              x, t);
  }
}

/// One accepted step, as a watcher sees it: [t0, t1], the states at its
/// ends (after the projection), and the state anywhere inside it (at, for
/// dense-output steppers: the interpolation, projected where the scene needs it).
template <class S, class State, class Stepping>
struct step_view {
  const S& scene;
  double t0, t1;
  const State& x0;
  const State& x1;
  const Stepping& stepping;
  void at(double t, State& x) const {
    static_assert(Stepping::dense, "flange: the state inside a step needs a dense-output stepper");
    stepping.at(t, x);
    if constexpr (needs_projection<S>()) restore_invariants(scene, x, t);
  }
};

/// The check that does nothing (integrate_projected, integrate_rosenbrock4:
/// the system given is checked as the caller chose).
struct no_step_check {
  template <class State>
  void after(const State&, double, const State&, double) const {}
  template <class State>
  void collapsing(const State&, double, double) const {}
};

/// A watcher that hands observer(x, t) the start and every step's end.
template <class Observer>
struct observe_steps {
  Observer& observer;
  template <class State>
  void start(const State& x, double t) {
    observer(x, t);
  }
  template <class View>
  void step(const View& v) {
    observer(v.x1, v.t1);
  }
};

/// Integrates x from t0 to t1 (see the file's comment). dt is the first
/// step's size (a fixed stepper's every step), signed like t1 − t0. Returns
/// the number of accepted steps; x holds the state at t1.
template <class Stepping, class System, class S, class State, class Watcher, class Check>
long integrate(Stepping& st, System& sys, const S& scene, State& x, double t0, double t1, double dt,
               Watcher& watcher, const Check& check) {
  constexpr bool project = needs_projection<S>();
  if (!finite(x)) [[unlikely]]
    fail_at("the state is not finite", x, t0);  // the initial state
  check_coordinates(scene, x);
  check_loops(scene, x);
  check_contact_depths(scene, x, t0, true);
  if constexpr (project) restore_invariants(scene, x, t0);
  st.start(x, t0, dt, t1);
  watcher.start(x, t0);
  const double end_slack = 16 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t0), std::abs(t1));
  long steps = 0;
  while (std::abs(t1 - st.time()) > end_slack && (t1 - st.time()) * (t1 - t0) > 0) {
    try {
      st.step(sys, t1);
    } catch (const step_collapse& c) {
      check.collapsing(st.state(), c.t, c.h);  // a non-finite stage is the true reason, if there is one
      fail_at(concat("the step size collapsed to ", c.h, " at t = ", c.t,
                     c.rejected > 0 ? concat(" after ", c.rejected, " rejected steps") : std::string(),
                     " (a discontinuity, a singularity, or a tolerance the stepper cannot meet in double "
                     "precision)"),
              st.state(), c.t);
    }
    check.after(st.previous_state(), st.previous_time(), st.state(), st.time());
    check_contact_depths(scene, st.state(), st.time(), false);
    if constexpr (project) {
      State y = st.state();
      restore_invariants(scene, y, st.time());
      st.restart(y);
    }
    ++steps;
    watcher.step(step_view<S, State, Stepping>{scene, st.previous_time(), st.time(), st.previous_state(),
                                               st.state(), st});
  }
  x = st.state();
  return steps;
}

}  // namespace detail

}  // namespace flange
