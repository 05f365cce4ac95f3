// One checked call for a whole run: the path that fails loudly by default.
//
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0);                    // dopri5 at 1e-8
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0, {.tolerance = 1e-12}, observer);
//   auto x1 = flange::simulate<method::rosenbrock4>(stiff, x0, 0.0, 10.0);   // rosenbrock4.hpp
//   auto tr = flange::simulate(arm, x0, flange::output_times(0.0, 10.0, 0.01));  // the trajectory
//   tr.t[k], tr.x[k]; tr.steps, tr.rhs_evals
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
// step's cost (docs/performance.md). Given output times, simulate returns the
// states at those times, each from the stepper's dense output inside the step
// that holds it (projected like the steps' ends where the scene needs it),
// with the step and evaluation counts. An ensemble's case runs the same loop
// with the same checks, so it ends bit for bit where simulate ends. The raw
// Odeint system (the scene itself) stays for those who want their own
// stepper; it neither checks nor projects.
#pragma once
#include <boost/numeric/odeint/integrate/null_observer.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "flange/detail/lazy.hpp"
#include "flange/errors.hpp"
#include "flange/simulate/checked.hpp"
#include "flange/simulate/integrate.hpp"
#include "flange/simulate/method.hpp"
#include "flange/simulate/options.hpp"
#include "flange/simulate/system.hpp"

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
template <class S, class Stepping, bool Shared>
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
      with_system<Shared, State>(sys, [&](auto& s) { st.step(s, t + h); });
    } catch (const step_collapse&) {
    }
  }
};

/// A checked run of the loop with a method: what simulate and an ensemble's
/// case both do. Returns the number of steps; evals counts the evaluations.
template <class Method, bool Shared = shared_steps<Method>, class S, class State, class Watcher>
long checked_run(const S& scene, State& x, double t0, double t1, const simulate_options& o, long& evals,
                 Watcher& watcher) {
  if constexpr (method_available<Method>()) {  // else one error, and nothing instantiated after it
    auto st = method_stepping<Method, State>(scene, o.abs_tol(), o.rel_tol());
    const checked_steps<S, decltype(st), Shared> check{&scene, st};
    counted_system<S> sys{&scene, &evals, o.max_rhs_evals};
    const double dt = (t1 >= t0 ? 1 : -1) * o.dt;
    return with_system<Shared, State>(
        sys, [&](auto& s) { return integrate(st, s, scene, x, t0, t1, dt, watcher, check); });
  } else {
    return 0L;
  }
}
/// The integration loop's watcher that keeps the states at the requested
/// times (already checked: at least two, strictly monotone, the first t0).
template <class State>
struct sample_times {
  const std::vector<double>& times;
  std::vector<double>& t;
  std::vector<State>& x;
  std::size_t next = 1;
  void start(const State& x0, double t0) {
    t.push_back(t0);
    x.push_back(x0);
  }
  template <class View>
  void step(const View& v) {
    const double dir = v.t1 >= v.t0 ? 1 : -1;
    for (; next < times.size() && dir * (v.t1 - times[next]) >= 0; ++next) {
      t.push_back(times[next]);
      x.push_back(v.x1);
      if (times[next] != v.t1) v.at(times[next], x.back());
    }
  }
};

/// Checks requested output times: at least two, finite, strictly monotone.
FLANGE_LAZY
void check_times(const std::vector<double>& times) {
  if (times.size() < 2)
    throw parameter_error(concat("flange: simulate: ", times.size(),
                                 " output time(s) given; give the start and at least one more"));
  const double dir = times[1] > times[0] ? 1 : -1;
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]))
      throw parameter_error(concat("flange: simulate: output time ", k, " is ", times[k], ", not finite"));
    if (k > 0 && !(dir * (times[k] - times[k - 1]) > 0))
      throw parameter_error(concat("flange: simulate: the output times must be strictly ",
                                   dir > 0 ? "increasing" : "decreasing", "; time ", k, " = ", times[k],
                                   " follows ", times[k - 1]));
  }
}
FLANGE_COMMON(void check_times<0>(const std::vector<double>&))
}  // namespace detail

/// A run's states at the requested times, and what it cost.
template <class State>
struct trajectory {
  std::vector<double> t;  ///< the requested times
  std::vector<State> x;   ///< the state at each
  long steps = 0;         ///< accepted steps
  long rhs_evals = 0;     ///< derivative evaluations (a Jacobian's own not counted)
  [[nodiscard]] std::size_t size() const { return t.size(); }
};

/// The named joint's state at each of a run's times (get_joint), a cut
/// joint's angles unwrapped along the run: the first as its frames place it,
/// within (−π, π], each next one within half a turn of the one before
/// carried forward by the mean of the two samples' rates. It stays
/// continuous while that estimate of the turn between two samples (the
/// trapezoid rule on the rate) is off by less than half a turn. A tree
/// joint's angles are state coordinates, continuous already.
template <fixed_string Name, class S, class State>
[[nodiscard]] std::vector<joint_state_t<typename detail::named_any_joint<S, Name>::type>> get_joint(
    const S& scene, const trajectory<State>& tr) {
  using N = detail::named_any_joint<S, Name>;
  std::vector<joint_state_t<typename N::type>> out;
  out.reserve(tr.size());
  if constexpr (N::cut >= 0) {
    using J = typename N::type;
    const auto& joint = scene.template component<N::index>();
    std::array<double, J::nq> q_before{}, qd_before{}, guess{}, qd{};
    for (std::size_t k = 0; k < tr.size(); ++k) {
      S::require_state_size(tr.x[k]);
      auto r = detail::read_cut_at<S, N::cut>(scene, tr.x[k].data(), tr.x[k].data() + S::n_q);
      joint.qdot(r.q.data(), r.v.data(), qd.data());  // an angle's rate does not depend on its turn
      if (k > 0) {
        for (int i = 0; i < J::nq; ++i) guess[i] = q_before[i] + 0.5 * (qd_before[i] + qd[i]) * (tr.t[k] - tr.t[k - 1]);
        detail::unwrap_angles<J>(r.q.data(), guess.data());
      }
      q_before = r.q;
      qd_before = qd;
      out.push_back(read_joint_value(joint, r.q.data(), r.v.data()));
    }
  } else {
    for (const auto& x : tr.x) out.push_back(get_joint<Name>(scene, x));
  }
  return out;
}

/// Times from t0 to t1 every dt: t0 + k·dt while before t1, and t1 itself
/// (a last interval shorter than dt, never one shorter than 1e-9·dt).
FLANGE_LAZY
std::vector<double> output_times(double t0, double t1, double dt) {
  if (!(std::isfinite(t0) && std::isfinite(t1) && t1 != t0))
    throw parameter_error(detail::concat("flange: output_times: needs finite t0 != t1 (got ", t0, ", ", t1, ")"));
  if (!(dt > 0 && std::isfinite(dt)))
    throw parameter_error(detail::concat("flange: output_times: the interval dt = ", dt, " must be positive"));
  const double span = std::abs(t1 - t0), dir = t1 > t0 ? 1 : -1;
  const auto n = static_cast<std::size_t>(std::ceil(span / dt - 1e-9));
  std::vector<double> times;
  times.reserve(n + 1);
  for (std::size_t k = 0; k < n; ++k) times.push_back(t0 + dir * static_cast<double>(k) * dt);
  times.push_back(t1);
  return times;
}
FLANGE_COMMON(std::vector<double> output_times<0>(double, double, double))

/// The state at t1 from x0 at t0; observer(x, t) sees the start and every
/// step. Method: method::dopri5 (the default), method::bulirsch_stoer
/// (simulate/bulirsch_stoer.hpp), method::rosenbrock4 (simulate/rosenbrock4.hpp)
/// or one's own (method.hpp).
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

/// The states at the requested times, times[0] the start (x0's time),
/// through the method's dense output, with the step and evaluation counts;
/// checked and projected as the run to one end time is. The trajectory's
/// storage is reserved before the first step: the loop allocates nothing.
template <class Method = method::dopri5, class S>
trajectory<typename S::state_type> simulate(const S& scene, const typename S::state_type& x0,
                                            const std::vector<double>& times, const simulate_options& o = {}) {
  detail::check_times(times);
  detail::check_run("simulate", o, times.front(), times.back());
  trajectory<typename S::state_type> tr;
  tr.t.reserve(times.size());
  tr.x.reserve(times.size());
  detail::sample_times<typename S::state_type> watch{times, tr.t, tr.x};
  auto x = x0;
  tr.steps = detail::checked_run<Method>(scene, x, times.front(), times.back(), o, tr.rhs_evals, watch);
  // The last step ends on t1 to round-off (t + (t1 − t) need not be t1): a
  // time it stopped a few ulp short of is the end state's.
  while (tr.t.size() < times.size()) {
    tr.t.push_back(times[tr.t.size()]);
    tr.x.push_back(x);
  }
  return tr;
}

}  // namespace flange
