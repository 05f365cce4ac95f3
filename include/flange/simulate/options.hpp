// How a run is integrated: one struct for every checked way to integrate a
// scene, simulate() and each case of an ensemble.
//
//   flange::simulate(arm, x0, 0.0, 10.0, {.tolerance = 1e-10});
//   ensemble::make(setup, 0.0, 20.0, {.tolerance = 1e-8, .max_rhs_evals = 1'000'000}, recorders…);
//
// A raw Odeint loop over checked(scene, budget) (checked.hpp) has no options:
// its stepper holds the tolerances, and the budget is the account its
// evaluations draw on.
#pragma once
#include <cmath>
#include <limits>
#include <optional>

#include "flange/detail/lazy.hpp"
#include "flange/errors.hpp"

namespace flange {

struct simulate_options {
  double tolerance = 1e-8;            ///< the error control's absolute tolerance, and its relative one
                                      ///< unless rel_tolerance is given
  double dt = 1e-3;                   ///< the first step's size
  long max_rhs_evals = 100'000'000;   ///< derivative evaluations allowed: beyond them the run (the case) fails
  std::optional<double> rel_tolerance{};  ///< a relative tolerance other than `tolerance`

  [[nodiscard]] double abs_tol() const { return tolerance; }
  [[nodiscard]] double rel_tol() const { return rel_tolerance.value_or(tolerance); }
};

namespace detail {
/// Checks a run's options and times; throws parameter_error naming `who`.
FLANGE_LAZY
void check_run(const char* who, const simulate_options& o, double t0, double t1) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const bool abs_ok = o.abs_tol() >= 10 * eps;
  const bool rel_ok = o.rel_tol() >= 10 * eps || o.rel_tol() == 0;  // 0: absolute error control only
  if (!abs_ok || !rel_ok)
    throw parameter_error(concat("flange: ", who, ": ", abs_ok ? "relative tolerance " : "tolerance ",
                                 abs_ok ? o.rel_tol() : o.abs_tol(),
                                 " cannot be met in double precision (round-off alone is ", eps,
                                 " per step); use 1e-14 or more", abs_ok ? ", or 0" : ""));
  if (!(std::isfinite(t0) && std::isfinite(t1)))
    throw parameter_error(concat("flange: ", who, ": the times t0 = ", t0, " and t1 = ", t1, " must be finite"));
  if (!(o.dt > 0))
    throw parameter_error(concat("flange: ", who, ": the first step dt = ", o.dt, " must be positive"));
  if (!(o.max_rhs_evals >= 1))
    throw parameter_error(concat("flange: ", who, ": max_rhs_evals = ", o.max_rhs_evals, " must be at least 1"));
}
FLANGE_COMMON(void check_run<0>(const char*, const simulate_options&, double, double))
}  // namespace detail

}  // namespace flange
