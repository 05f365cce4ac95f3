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
// and lets the derivative's own errors (singular mass matrix) through.
// b.rhs_evals counts the evaluations, so b also reports the cost of a run.
#pragma once
#include "flange/detail/inline.hpp"
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "flange/errors.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

struct budget {
  long max_rhs_evals = std::numeric_limits<long>::max();
  long rhs_evals = 0;  ///< evaluations made so far (across copies of the checked system)
};

namespace detail {
template <class State>
std::string describe(const State& x) {
  std::ostringstream os;
  os.precision(17);
  os << "x = [";
  for (std::size_t i = 0; i < x.size(); ++i) os << (i ? ", " : "") << static_cast<double>(x[i]);
  os << "]";
  return os.str();
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
  throw simulation_error(concat("flange: ", why, " at t = ", static_cast<double>(t), ", ", describe(x)),
                         static_cast<double>(t));
}
inline std::string budget_spent(long max_rhs_evals) {
  return "the budget of " + std::to_string(max_rhs_evals) +
         " derivative evaluations is spent (a stiff scene for an explicit stepper? try rosenbrock4)";
}
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
