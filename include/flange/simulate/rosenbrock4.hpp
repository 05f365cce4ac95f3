// Stiff integration with Odeint's rosenbrock4 and the exact Jacobian.
//
//   auto steps = flange::integrate_rosenbrock4(scene, x, 0.0, 10.0, 1e-3, 1e-8, 1e-8);
//
// Link the optional library flange::rosenbrock4 (src/rosenbrock4.cpp): Odeint's
// rosenbrock4 needs uBLAS, which in Boost 1.74 does not compile as C++20, so it
// is built as C++17 and called through function pointers. The Jacobian comes
// from dual numbers (simulate/jacobian.hpp). Exceptions thrown in the
// derivative (a singular mass matrix, …) are carried across and rethrown.
//
// Time is integrated as an extra state τ with τ' = 1, so rosenbrock4 sees an
// autonomous system and ∂f/∂t enters as the Jacobian column ∂f/∂τ. This is not
// optional: Boost 1.74's rosenbrock4 handles the explicit time derivative
// wrongly and falls to first order on a time-dependent system, even with the
// exact ∂f/∂t (for x' = cos t: error 7e-4 at tolerance 1e-6, falling only 10×
// per 100× tighter tolerance; tests/jacobian_test.cpp shows the repair).
#pragma once
#include <exception>

#include "flange/simulate/jacobian.hpp"
#include "flange/simulate/rosenbrock4_bridge.h"

namespace flange {

/// How integrate_rosenbrock4 gets its Jacobian.
namespace jacobian_method {
struct exact {};              ///< dual numbers: one evaluation, exact to round-off (the default)
struct finite_difference {};  ///< central differences, for comparison: 2·(n + 1) evaluations for n states
}  // namespace jacobian_method

/// What a rosenbrock4 run cost. Each step attempt, accepted or rejected,
/// evaluates one Jacobian, so rejected = jacobian_evals − steps.
struct stiff_stats {
  long rhs_evals = 0;
  long jacobian_evals = 0;
  long steps = 0;
};

/// Integrates x from t0 to t1 with rosenbrock4; observer(x, t) is called at
/// every step, or every observe_dt when observe_dt > 0. Returns the step count;
/// stats, if given, receives the evaluation counts (the derivative
/// evaluations inside a finite-difference Jacobian are not among rhs_evals).
/// integrate_rosenbrock4<jacobian_method::finite_difference>(…) swaps the
/// exact Jacobian for central differences.
template <class Method = jacobian_method::exact, class S, class State, class Observer = std::nullptr_t>
std::size_t integrate_rosenbrock4(const S& scene, State& x, double t0, double t1, double dt, double abs_tol,
                                  double rel_tol, Observer observer = nullptr, double observe_dt = 0,
                                  stiff_stats* stats = nullptr) {
  S::require_state_size(x);
  constexpr int n = S::n_state;  // the augmented state is (x, τ): n + 1
  struct context {
    const S* scene;
    Observer* observer;
    std::exception_ptr error;
    stiff_stats counts;
  } ctx{&scene, &observer, nullptr, {}};
  flange_stiff_callbacks cb{};
  cb.context = &ctx;
  cb.n = n + 1;
  cb.f = [](void* c, const double* xs, double* d, double) {
    auto& k = *static_cast<context*>(c);
    ++k.counts.rhs_evals;
    try {
      std::array<double, n> a, b;
      std::copy_n(xs, n, a.begin());
      (*k.scene)(a, b, xs[n]);
      std::copy_n(b.begin(), n, d);
      d[n] = 1;  // τ' = 1
    } catch (...) {
      k.error = std::current_exception();
      throw;
    }
  };
  cb.jacobian = [](void* c, const double* xs, double* J, double* dfdt, double) {
    auto& k = *static_cast<context*>(c);
    ++k.counts.jacobian_evals;
    try {
      std::array<double, n> a;
      std::copy_n(xs, n, a.begin());
      Eigen::Matrix<double, n, 1> ft;
      const auto Je = [&] {
        if constexpr (std::is_same_v<Method, jacobian_method::finite_difference>)
          return jacobian_finite_difference(*k.scene, xs[n], a, &ft);
        else return jacobian(*k.scene, xs[n], a, &ft);
      }();
      constexpr int m = n + 1;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) J[i * m + j] = Je(i, j);
        J[i * m + n] = ft(i);  // ∂f/∂τ
      }
      for (int j = 0; j < m; ++j) J[n * m + j] = 0;  // τ' = 1 depends on nothing
      for (int i = 0; i < m; ++i) dfdt[i] = 0;       // autonomous
    } catch (...) {
      k.error = std::current_exception();
      throw;
    }
  };
  if constexpr (!std::is_same_v<Observer, std::nullptr_t>) {
    cb.observe = [](void* c, const double* xs, double t) {
      auto& k = *static_cast<context*>(c);
      State s;
      std::copy_n(xs, n, s.begin());
      (*k.observer)(s, t);
    };
  }
  std::array<double, n + 1> xs;
  std::copy_n(x.begin(), n, xs.begin());
  xs[n] = t0;
  const long steps = flange_rosenbrock4_integrate(&cb, xs.data(), t0, t1, dt, abs_tol, rel_tol, observe_dt);
  if (steps < 0) {
    if (ctx.error) std::rethrow_exception(ctx.error);
    throw simulation_error("flange: rosenbrock4 failed", t0);
  }
  std::copy_n(xs.begin(), n, x.begin());
  if (stats) {
    *stats = ctx.counts;
    stats->steps = steps;
  }
  return static_cast<std::size_t>(steps);
}

}  // namespace flange
