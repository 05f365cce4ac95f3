// Stiff integration with Odeint's rosenbrock4 and the exact Jacobian.
//
//   auto steps = flange::integrate_rosenbrock4(scene, x, 0.0, 10.0, 1e-3, 1e-8, 1e-8);
//
// Header-only, like the rest of flange: Odeint's rosenbrock4 works on uBLAS
// vectors and matrices, which compile as C++20 from Boost 1.81 on (Boost
// 1.74's uBLAS called std::allocator::construct, which C++20 removed, and
// needed a separately compiled C++17 bridge). The Jacobian comes from dual
// numbers (simulate/jacobian.hpp), or central differences on request.
// Exceptions thrown in the derivative (a singular mass matrix, …) pass
// through the stepper to the caller.
//
// Time is integrated as an extra state τ with τ' = 1, so rosenbrock4 sees an
// autonomous system and ∂f/∂t enters as the Jacobian column ∂f/∂τ. Boost
// 1.74's rosenbrock4 handled the explicit time derivative wrongly and fell to
// first order on a time-dependent system (for x' = cos t: error 7e-4 at
// tolerance 1e-6, falling only 10× per 100× tighter tolerance;
// tests/jacobian_test.cpp keeps the check); the augmented form is right in
// every version.
//
// uBLAS vectors live on the heap: unlike the explicit steppers, this one
// allocates (Odeint's, per step), which is why it is not in the no-heap test.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <type_traits>

#include <boost/numeric/odeint/integrate/integrate_adaptive.hpp>
#include <boost/numeric/odeint/integrate/integrate_const.hpp>
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_controller.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_dense_output.hpp>

#include "flange/simulate/jacobian.hpp"

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
  namespace odeint = boost::numeric::odeint;
  using vector = boost::numeric::ublas::vector<double>;
  using matrix = boost::numeric::ublas::matrix<double>;
  S::require_state_size(x);
  constexpr int n = S::n_state;  // the augmented state is (x, τ): n + 1
  stiff_stats counts;
  auto f = [&](const vector& xs, vector& d, double) {
    ++counts.rhs_evals;
    std::array<double, n> a, b;
    std::copy_n(xs.begin(), n, a.begin());
    scene(a, b, xs[n]);
    std::copy_n(b.begin(), n, d.begin());
    d[n] = 1;  // τ' = 1
  };
  auto jac = [&](const vector& xs, matrix& J, double, vector& dfdt) {
    ++counts.jacobian_evals;
    std::array<double, n> a;
    std::copy_n(xs.begin(), n, a.begin());
    Eigen::Matrix<double, n, 1> ft;
    const auto Je = [&] {
      if constexpr (std::is_same_v<Method, jacobian_method::finite_difference>)
        return jacobian_finite_difference(scene, xs[n], a, &ft);
      else return jacobian(scene, xs[n], a, &ft);
    }();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) J(i, j) = Je(i, j);
      J(i, n) = ft(i);  // ∂f/∂τ
    }
    for (int j = 0; j <= n; ++j) J(n, j) = 0;  // τ' = 1 depends on nothing
    for (int i = 0; i <= n; ++i) dfdt[i] = 0;  // autonomous
  };
  auto observe = [&](const vector& xs, double t) {
    if constexpr (!std::is_same_v<Observer, std::nullptr_t>) {
      State s = x;
      std::copy_n(xs.begin(), n, s.begin());
      observer(s, t);
    } else {
      (void)xs, (void)t;
    }
  };
  vector xs(n + 1);
  std::copy_n(x.begin(), n, xs.begin());
  xs[n] = t0;
  auto stepper = odeint::make_dense_output(abs_tol, rel_tol, odeint::rosenbrock4<double>());
  const auto system = std::make_pair(f, jac);
  const std::size_t steps = observe_dt > 0
                                ? odeint::integrate_const(stepper, system, xs, t0, t1, observe_dt, observe)
                                : odeint::integrate_adaptive(stepper, system, xs, t0, t1, dt, observe);
  std::copy_n(xs.begin(), n, x.begin());
  if (stats) {
    *stats = counts;
    stats->steps = static_cast<long>(steps);
  }
  return steps;
}

}  // namespace flange
