// One checked call for a whole run: the path that fails loudly by default.
//
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0);                    // dopri5 at 1e-8
//   auto x1 = flange::simulate(arm, x0, 0.0, 10.0, {.tolerance = 1e-12}, observer);
//
// It steps a controlled dopri5 through checked(scene, budget)
// (checked.hpp) with a projection after every step (integrate_projected,
// projected.hpp: loops closed, quaternions normalised), so a non-finite
// state or derivative, a spent budget, a singular mass matrix, a loop left
// open or a step size that collapses each throw, with the time, the state
// and the reason. The raw Odeint system (the scene itself) stays for those
// who want their own stepper; it checks nothing.
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
  budget b{.max_rhs_evals = o.max_rhs_evals};
  auto stepper = odeint::make_controlled(o.tolerance, o.tolerance, odeint::runge_kutta_dopri5<typename S::state_type>());
  integrate_projected(stepper, checked(scene, b), scene, x0, t0, t1, (t1 > t0 ? 1 : -1) * o.dt, observer);
  return x0;
}

}  // namespace flange
