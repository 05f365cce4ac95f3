// The measuring tools of a work-precision study: how much error a stepper
// leaves at the final time, and what it cost to get there.
//
//   auto ref = study::long_double_reference(scene, x0, T);     // and its error
//   auto x = x0;
//   auto c = study::integrate_controlled(odeint::make_controlled(tol, tol,
//                odeint::runge_kutta_dopri5<X>()), scene, x, 0.0, T, 1e-3);
//   double e = study::scaled_error(x, ref.x);                   // c.rhs_evals, c.steps, c.rejected
//   double s = study::median_seconds([&] { … one run … }, 5);
//
// The error of a state x against a reference r is the largest scaled
// component error, max_i |x_i − r_i| / (1 + |r_i|): absolute for components
// near zero, relative for large ones, as Odeint's own error control with
// abs_tol = rel_tol measures it.
//
// Nothing here is timed in the tests (tests/work_precision_test.cpp checks
// the error measure, the counts and the convergence on a harmonic
// oscillator); benchmarks/work_precision.cpp runs the study.
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "flange/errors.hpp"
#include "flange/simulate/odeint.hpp"

namespace flange::study {

/// max_i |x_i − r_i| / (1 + |r_i|), in double. Non-finite x gives +∞.
template <class X, class R>
double scaled_error(const X& x, const R& ref) {
  double worst = 0;
  for (std::size_t i = 0; i < std::size(ref); ++i) {
    const long double xi = static_cast<long double>(x[i]), ri = static_cast<long double>(ref[i]);
    if (!std::isfinite(static_cast<double>(xi))) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, static_cast<double>(std::abs(xi - ri) / (1 + std::abs(ri))));
  }
  return worst;
}

/// What a run cost.
struct cost {
  long rhs_evals = 0;       ///< derivative evaluations
  long steps = 0;           ///< accepted steps
  long rejected = 0;        ///< rejected step attempts (controlled steppers)
  long jacobian_evals = 0;  ///< Jacobians (rosenbrock4)
};

/// A system that counts its evaluations.
template <class Sys>
struct counted {
  const Sys* sys;
  long* evals;
  template <class State, class T>
  void operator()(const State& x, State& dxdt, T t) const {
    ++*evals;
    (*sys)(x, dxdt, t);
  }
};

/// Integrates x from t0 to t1 with a controlled stepper (Odeint's
/// controlled_runge_kutta or bulirsch_stoer): the loop of integrate_adaptive,
/// which also counts the rejected attempts. The last step is shortened to end
/// at t1. Throws simulation_error after max_attempts attempts.
template <class Controlled, class Sys, class State, class T>
cost integrate_controlled(Controlled stepper, const Sys& sys, State& x, T t0, T t1, T dt, long max_attempts = 50'000'000) {
  cost c;
  const counted<Sys> f{&sys, &c.rhs_evals};
  T t = t0;
  const T end_slack = 8 * std::numeric_limits<T>::epsilon() * std::max(T(1), std::abs(t1));
  while (t1 - t > end_slack) {
    if (t + dt > t1) dt = t1 - t;
    if (stepper.try_step(f, x, t, dt) == odeint::success)
      ++c.steps;
    else
      ++c.rejected;
    if (c.steps + c.rejected > max_attempts)
      throw simulation_error(detail::concat("flange::study: more than ", max_attempts, " step attempts"),
                             static_cast<double>(t));
  }
  return c;
}

/// Integrates x from t0 to t1 in n equal steps of a fixed-step stepper.
template <class Stepper, class Sys, class State, class T>
cost integrate_fixed(Stepper stepper, const Sys& sys, State& x, T t0, T t1, long n) {
  cost c;
  const counted<Sys> f{&sys, &c.rhs_evals};
  const T dt = (t1 - t0) / static_cast<T>(n);
  for (long i = 0; i < n; ++i) stepper.do_step(f, x, t0 + static_cast<T>(i) * dt, dt);
  c.steps = n;
  return c;
}

/// A reference solution in long double and an estimate of its own error:
/// fehlberg78 at tolerance `tight` gives x; a second solve at `loose`
/// (10× looser by default) differs from it by about the looser solve's error,
/// an upper bound on the tighter one's, reported as error_estimate.
struct reference {
  std::vector<long double> x;
  double error_estimate;
  long rhs_evals;
};
/// The reference's stepper: fehlberg78, or dopri5 where fehlberg78's error
/// estimate is blind (it weighs only the first and the last three stages, so
/// a step that flies from the air into a contact within its middle stages
/// can pass: contact scenes).
enum class reference_stepper { fehlberg78, dopri5 };
template <class S, class X>
reference long_double_reference(const S& scene, const X& x0, double t1, long double tight = 1e-18L,
                                long double loose = 1e-17L,
                                reference_stepper method = reference_stepper::fehlberg78) {
  using L = std::array<long double, std::tuple_size_v<X>>;
  auto solve = [&](long double tol, long& evals) {
    L x;
    std::copy(x0.begin(), x0.end(), x.begin());
    if (method == reference_stepper::fehlberg78) {
      auto stepper = odeint::make_controlled<odeint::runge_kutta_fehlberg78<L, long double>>(tol, tol);
      evals += integrate_controlled(stepper, scene, x, 0.0L, static_cast<long double>(t1), 1e-4L).rhs_evals;
    } else {
      auto stepper = odeint::make_controlled<odeint::runge_kutta_dopri5<L, long double>>(tol, tol);
      evals += integrate_controlled(stepper, scene, x, 0.0L, static_cast<long double>(t1), 1e-4L).rhs_evals;
    }
    return x;
  };
  long evals = 0;
  const L x = solve(tight, evals), y = solve(loose, evals);
  return {std::vector<long double>(x.begin(), x.end()), scaled_error(y, x), evals};
}

/// The median over `repeats` of the wall time of one call of run(), in
/// seconds. Each sample runs run() often enough to take at least
/// min_sample seconds, so short runs are not lost in the clock's resolution.
template <class F>
double median_seconds(F&& run, int repeats = 5, double min_sample = 2e-3) {
  using clock = std::chrono::steady_clock;
  auto time = [&](long n) {
    const auto start = clock::now();
    for (long i = 0; i < n; ++i) run();
    return std::chrono::duration<double>(clock::now() - start).count();
  };
  long n = 1;
  for (double s = time(1); s < min_sample && n < (1L << 20); s = time(n)) n *= 2;
  std::vector<double> samples;
  for (int r = 0; r < repeats; ++r) samples.push_back(time(n) / static_cast<double>(n));
  std::sort(samples.begin(), samples.end());
  return samples[samples.size() / 2];
}

/// A point of a work-precision diagram.
struct point {
  std::string scene, stepper;
  std::string control;  ///< "tol" (tolerance) or "dt" (fixed step)
  double tolerance;     ///< the tolerance, or the step size
  double error;
  double seconds_per_sim_second;
  cost c;
};

/// The cheapest point with error ≤ band, or nullptr.
inline const point* cheapest(const std::vector<point>& points, const std::string& scene, double band) {
  const point* best = nullptr;
  for (const auto& p : points)
    if (p.scene == scene && p.error <= band && (!best || p.seconds_per_sim_second < best->seconds_per_sim_second))
      best = &p;
  return best;
}

}  // namespace flange::study
