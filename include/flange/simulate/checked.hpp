// A checked system: the scene wrapped so that any Odeint stepper and integrate
// function fails loudly instead of quietly.
//
//   flange::budget b{.max_rhs_evals = 100000};
//   odeint::integrate_adaptive(stepper, flange::checked(scene, b), x, t0, t1, dt);
//
// It throws flange::simulation_error, with the time, the state and the reason,
//   * when the state or the derivative is not finite (a NaN never propagates
//     into a trajectory), or the initial joint coordinates are not valid (a
//     quaternion far from unit norm: an input mistake, not drift) or do not
//     close the scene's loops,
//   * when the budget of derivative evaluations is spent: the usual sign that
//     an explicit stepper meets a stiff scene (Boost 1.74's max_step_checker
//     does not stop a controlled stepper in integrate_const; this does),
//   * when the state has drifted off the scene's invariants by more than
//     budget::max_drift: a raw Odeint stepper does not project, so a loop
//     opens and a quaternion leaves unit norm as the steps' errors add up
//     (simulate, integrate_projected and the ensembles project after every
//     step and never drift). The drift is |Φ_i| / L for a loop's constraint
//     row (L the scene's length scale, at least 1 m) and the largest change
//     normalize would make to a joint's coordinate (|‖q‖ − 1| for a
//     quaternion). A stepper's trial stages lie off the constraints by their
//     own error, so only a drift that every one of 256 evaluations in a row
//     shows is reported: some accepted state, evaluated as every stepper
//     evaluates it, is among them. Scenes without loops or quaternions do
//     not pay for the check.
// and lets the derivative's own errors (singular mass matrix) through.
// b.rhs_evals counts the evaluations, so b also reports the cost of a run.
#pragma once
#include "flange/detail/inline.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "flange/detail/lazy.hpp"
#include "flange/errors.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

struct budget {
  long max_rhs_evals = std::numeric_limits<long>::max();
  long rhs_evals = 0;       ///< evaluations made so far (across copies of the checked system)
  double max_drift = 1e-6;  ///< the largest drift off the invariants that goes on (see above)
  // The checked system's own: the least drift seen in the current window of evaluations.
  double drift_least = std::numeric_limits<double>::infinity();
  int drift_window = 0;
};

namespace detail {
template <class State>
std::string describe(const State& x) {
  std::string out = "x = [";
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i) out += ", ";
    append_number(out, static_cast<double>(x[i]));
  }
  out += "]";
  return out;
}
template <class State>
bool finite(const State& x) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(static_cast<double>(x[i]))) return false;
  return true;
}
/// Throws simulation_error "flange: <why> at t = …, x = […]".
template <class State, class T>
[[noreturn, gnu::cold]] void fail_at(const std::string& why, const State& x, const T& t) {
  std::vector<double> state(x.size());
  for (std::size_t i = 0; i < state.size(); ++i) state[i] = static_cast<double>(x[i]);
  throw simulation_error(concat("flange: ", why, " at t = ", static_cast<double>(t), ", ", describe(x)),
                         static_cast<double>(t), std::move(state), why);
}
/// How far a state is off the scene's invariants, and where most.
struct drift_report {
  double value = 0;  ///< |Φ_i| / L, or the largest change normalize makes to a coordinate
  int joint = -1;    ///< the joint whose coordinates are furthest off, if they are the worst
  int row = -1;      ///< the loop row furthest off, if it is the worst
};
template <class S, class State>
drift_report invariant_drift(const S& scene, const State& x) {
  drift_report d;
  for_links<S>([&](auto l) {
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (normalizes<typename S::template component_type<LI::joint>>()) {
      std::array<double, LI::nq> q;
      for (int i = 0; i < LI::nq; ++i) q[i] = static_cast<double>(x[LI::q + i]);
      normalize_joint(scene.template component<LI::joint>(), q.data());
      for (int i = 0; i < LI::nq; ++i) {
        const double e = std::abs(q[i] - static_cast<double>(x[LI::q + i]));
        if (!(e <= d.value)) d = {e, LI::joint, -1};
      }
    }
  });
  if constexpr (has_loops<S>) {
    std::array<double, S::n_q> q;
    for (int i = 0; i < S::n_q; ++i) q[i] = static_cast<double>(x[i]);
    const std::array<double, S::n_v> zero{};
    const auto k = loop_kinematics<S>(scene, q.data(), zero.data());
    const double L = length_scale(scene);
    for (int i = 0; i < n_constraints<S>(); ++i)
      if (!(std::abs(k.phi[i]) / L <= d.value)) d = {std::abs(k.phi[i]) / L, -1, i};
  }
  return d;
}

FLANGE_LAZY
[[gnu::cold]] std::string budget_spent(long max_rhs_evals) {
  return concat("the budget of ", max_rhs_evals,
                " derivative evaluations is spent (a stiff scene for an explicit stepper? try rosenbrock4)");
}
FLANGE_COMMON(std::string budget_spent<0>(long))
}  // namespace detail

template <class S>
struct checked_system {
  const S* scene;
  budget* b;
  std::shared_ptr<budget> owned{};  ///< the budget, when checked() was given a temporary one
  template <class State, class T>
  FLANGE_INLINE void operator()(const State& x, State& dxdt, const T t) const {
    if (++b->rhs_evals > b->max_rhs_evals) [[unlikely]]
      detail::fail_at(detail::budget_spent(b->max_rhs_evals), x, t);
    if (!detail::finite(x)) [[unlikely]]
      detail::fail_at("the state is not finite", x, t);
    // Joint coordinates are checked at the first evaluation only: that is the
    // user's initial state. Later evaluations include a stepper's trial
    // stages, which may lie anywhere off the unit sphere before a step is
    // rejected.
    if (b->rhs_evals == 1) [[unlikely]]
      check_initial(x, t);
    if constexpr (detail::needs_projection<S>()) check_drift(x, t);
    (*scene)(x, dxdt, t);
    if (!detail::finite(dxdt)) [[unlikely]]
      detail::fail_at("the derivative is not finite", x, t);
  }

 private:
  /// Out of line: operator() is compiled into every stage of a stepper.
  template <class State, class T>
  [[gnu::cold, gnu::noinline]] void check_initial(const State& x, const T t) const {
    try {
      check_coordinates(*scene, x);
      check_loops(*scene, x);
    } catch (const parameter_error& e) {
      detail::fail_at(e.what(), x, t);
    }
  }
  /// Reports a drift that every evaluation of a window of 256 shows.
  template <class State, class T>
  void check_drift(const State& x, const T t) const {
    b->drift_least = std::min(b->drift_least, detail::invariant_drift(*scene, x).value);
    if (++b->drift_window < drift_window) return;
    const double least = b->drift_least;
    b->drift_least = std::numeric_limits<double>::infinity();
    b->drift_window = 0;
    if (least > b->max_drift) [[unlikely]]
      report_drift(x, t, least);
  }
  template <class State, class T>
  [[gnu::cold, gnu::noinline]] void report_drift(const State& x, const T t, double least) const {
    const auto d = detail::invariant_drift(*scene, x);
    const std::string what =
        d.row >= 0 ? detail::concat(detail::describe_loop(*scene, d.row), " is open: its frames are ",
                                    detail::loop_gap<S>(d.row, d.value * detail::length_scale(*scene)))
                   : detail::concat("the coordinates of ", detail::describe_component(*scene, d.joint),
                                    " are ", d.value, " off valid (a quaternion off unit norm)");
    detail::fail_at(detail::concat("the state has drifted off the scene's invariants: ", what, ", and every one of ",
                                   drift_window, " evaluations in a row was more than ", least,
                                   " off (budget::max_drift = ", b->max_drift,
                                   "); a raw Odeint stepper does not project: integrate with simulate() or "
                                   "integrate_projected, which keep them, or raise max_drift"),
                    x, t);
  }
  static constexpr int drift_window = 256;
};

/// The scene as a checked Odeint system; b must outlive the integration.
template <class S>
checked_system<S> checked(const S& scene, budget& b) {
  return {&scene, &b};
}
/// The same with a budget of its own, shared by the system's copies (the
/// one-liner checked(scene, budget{.max_rhs_evals = 1e5})). Allocated once,
/// here, never while stepping.
template <class S>
checked_system<S> checked(const S& scene, budget&& b) {
  auto owned = std::make_shared<budget>(b);
  budget* raw = owned.get();
  return {&scene, raw, std::move(owned)};
}

}  // namespace flange
