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
// It runs the integration loop (integrate.hpp) like every other path, so a
// scene with loops or quaternions is projected after every step, and
// method::rosenbrock4 is also a method of simulate<Method> and of the
// ensembles (method.hpp).
//
// uBLAS vectors live on the heap: unlike the explicit steppers, this one
// allocates (Odeint's, per step), which is why it is not in the no-heap test.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <utility>
#include <type_traits>

#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_controller.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_dense_output.hpp>

#include "flange/simulate/integrate.hpp"
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

namespace detail {
/// rosenbrock4 as the integration loop drives it (stepping.hpp): Odeint's
/// rosenbrock4 with dense output on the uBLAS state (x, τ), whose Jacobian
/// comes from the scene (Method: jacobian_method::exact or
/// finite_difference). The system the loop hands it gives the derivative.
template <class S, class State, class Method>
class rosenbrock4_stepping {
  using vector = boost::numeric::ublas::vector<double>;
  using matrix = boost::numeric::ublas::matrix<double>;
  static constexpr int n = S::n_state;  // the augmented state is (x, τ): n + 1
  using dense_stepper = boost::numeric::odeint::rosenbrock4_dense_output<
      boost::numeric::odeint::rosenbrock4_controller<boost::numeric::odeint::rosenbrock4<double>>>;

 public:
  static constexpr bool dense = true;
  rosenbrock4_stepping(const S& scene, double abs_tol, double rel_tol)
      : scene_(&scene), st_(boost::numeric::odeint::make_dense_output(abs_tol, rel_tol,
                                                                       boost::numeric::odeint::rosenbrock4<double>())),
        xs_(n + 1) {}
  void start(const State& x, double t, double dt, double t1) {
    x_ = x;
    load(x, t);
    st_.initialize(xs_, t, dt);
    tiny_ = tiny_step(t, t1);
  }
  template <class System>
  void step(System& sys, double t1) {
    auto f = [&](const vector& xs, vector& d, double) {
      ++stats_.rhs_evals;
      State a = x_, b = x_;
      std::copy_n(xs.begin(), n, a.begin());
      sys(a, b, xs[n]);
      std::copy_n(b.begin(), n, d.begin());
      d[n] = 1;  // τ' = 1
    };
    auto jac = [&](const vector& xs, matrix& J, double, vector& dfdt) {
      ++stats_.jacobian_evals;
      State a = x_;
      std::copy_n(xs.begin(), n, a.begin());
      Eigen::Matrix<double, n, 1> ft;
      if constexpr (std::is_same_v<Method, jacobian_method::finite_difference>)
        jacobian_finite_difference(*scene_, xs[n], a, J_, &ft);
      else
        jacobian(*scene_, xs[n], a, J_, &ft);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) J(i, j) = J_(i, j);
        J(i, n) = ft(i);  // ∂f/∂τ
      }
      for (int j = 0; j <= n; ++j) J(n, j) = 0;  // τ' = 1 depends on nothing
      for (int i = 0; i <= n; ++i) dfdt[i] = 0;  // autonomous
    };
    const double t = st_.current_time();
    if (passes(t, st_.current_time_step(), t1)) st_.initialize(st_.current_state(), t, t1 - t);
    prev_ = x_;
    try {
      st_.do_step(std::make_pair(f, jac));
    } catch (const boost::numeric::odeint::step_adjustment_error&) {
      throw step_collapse{t, static_cast<double>(st_.current_time_step()), max_rejections};
    }
    std::copy_n(st_.current_state().begin(), n, x_.begin());
    if (std::abs(st_.current_time_step()) < tiny_ && std::abs(t1 - st_.current_time()) > tiny_) [[unlikely]]
      throw step_collapse{st_.current_time(), static_cast<double>(st_.current_time_step()), 0};
  }
  void restart(const State& x) {
    x_ = x;
    load(x, st_.current_time());
    st_.initialize(xs_, st_.current_time(), st_.current_time_step());
  }
  const State& state() const { return x_; }
  const State& previous_state() const { return prev_; }
  double time() const { return st_.current_time(); }
  double previous_time() const { return st_.previous_time(); }
  void at(double t, State& x) const {
    vector y(n + 1);
    st_.calc_state(t, y);
    std::copy_n(y.begin(), n, x.begin());
  }
  const stiff_stats& stats() const { return stats_; }

 private:
  void load(const State& x, double t) {
    std::copy_n(x.begin(), n, xs_.begin());
    xs_[n] = t;
  }
  const S* scene_;
  mutable dense_stepper st_;  // its calc_state is not const
  vector xs_;
  jacobian_matrix<S> J_ = make_jacobian_matrix<S>();  // made once: a large scene's is on the heap
  State x_{}, prev_{};
  double tiny_ = 0;
  stiff_stats stats_;
};

/// A watcher that hands observer(x, t) the states at t0, t0 + Δ, t0 + 2Δ,
/// … up to t1, from the stepper's interpolation.
template <class Observer, class State>
struct observe_every {
  Observer& observer;
  double t0, delta;
  long k = 1;
  void start(const State& x, double t) { observer(x, t); }
  template <class View>
  void step(const View& v) {
    const double dir = v.t1 >= v.t0 ? 1 : -1;
    for (double tk = t0 + static_cast<double>(k) * delta; dir * (v.t1 - tk) >= 0;
         tk = t0 + static_cast<double>(++k) * delta) {
      if (tk == v.t1) {
        observer(v.x1, tk);
      } else {
        State x = v.x1;
        v.at(tk, x);
        observer(x, tk);
      }
    }
  }
};
}  // namespace detail

namespace method {
/// rosenbrock4 with the exact Jacobian (or, with
/// rosenbrock4_with<jacobian_method::finite_difference>, central differences).
template <class Jacobian = jacobian_method::exact>
struct rosenbrock4_with {
  template <class X, class S>
  static auto stepping(const S& scene, double abs_tol, double rel_tol) {
    return detail::rosenbrock4_stepping<S, X, Jacobian>(scene, abs_tol, rel_tol);
  }
};
using rosenbrock4 = rosenbrock4_with<>;
}  // namespace method

/// Integrates x from t0 to t1 with rosenbrock4, projected after every step
/// where the scene needs it; observer(x, t) is called at the start and
/// every step, or every observe_dt when observe_dt > 0. Returns the step
/// count; stats, if given, receives the evaluation counts (the derivative
/// evaluations inside a finite-difference Jacobian are not among rhs_evals).
/// integrate_rosenbrock4<jacobian_method::finite_difference>(…) swaps the
/// exact Jacobian for central differences.
template <class Method = jacobian_method::exact, class S, class State, class Observer = std::nullptr_t>
std::size_t integrate_rosenbrock4(const S& scene, State& x, double t0, double t1, double dt, double abs_tol,
                                  double rel_tol, Observer observer = nullptr, double observe_dt = 0,
                                  stiff_stats* stats = nullptr) {
  S::require_state_size(x);
  detail::rosenbrock4_stepping<S, State, Method> st(scene, abs_tol, rel_tol);
  auto sys = std::cref(scene);
  auto call = [&](const State& y, double t) {
    if constexpr (!std::is_same_v<Observer, std::nullptr_t>) observer(y, t);
    else (void)y, (void)t;
  };
  const double h = (t1 >= t0 ? 1 : -1) * std::abs(dt);
  long steps = 0;
  if (observe_dt > 0) {
    detail::observe_every<decltype(call), State> watch{call, t0, (t1 >= t0 ? 1 : -1) * observe_dt};
    steps = detail::integrate(st, sys, scene, x, t0, t1, h, watch, detail::no_step_check{});
  } else {
    detail::observe_steps<decltype(call)> watch{call};
    steps = detail::integrate(st, sys, scene, x, t0, t1, h, watch, detail::no_step_check{});
  }
  if (stats) {
    *stats = st.stats();
    stats->steps = steps;
  }
  return static_cast<std::size_t>(steps);
}

}  // namespace flange
