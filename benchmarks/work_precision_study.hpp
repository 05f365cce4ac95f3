// The work-precision study's parts (benchmarks/work_precision.cpp): the
// options, and the study of one scene over every stepper that applies. The
// scenes are studied in three units (work_precision_scenes_*.cpp), so that
// they compile side by side.
#pragma once
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>
#include <flange/study/work_precision.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

namespace work_precision {
using namespace flange;

struct options {
  bool quick = false;
  std::string csv, scene, reference_out;
};

template <class X>
inline void keep(const X& x) {
  asm volatile("" : : "r"(&x) : "memory");  // the result is used: the run cannot be optimised away
}

/// The study of one scene; symplectic = its Hamiltonian is separable
/// (constant mass matrix, no velocity-dependent forces).
template <class S>
void study_scene(const std::string& name, const S& s, typename S::state_type x0, double T, bool symplectic,
                 const options& o, std::vector<study::point>& out, std::ostream& refs,
                 study::reference_stepper reference = study::reference_stepper::fehlberg78) {
  if (!o.scene.empty() && o.scene != name) return;
  using X = typename S::state_type;
  const auto ref = study::long_double_reference(s, x0, T, 1e-18L, 1e-17L, reference);
  std::cout << "\n## " << name << ": " << S::n_v << " degrees of freedom, T = " << T << " s\n"
            << "reference: " << (reference == study::reference_stepper::dopri5 ? "dopri5" : "fehlberg78")
            << " in long double at 1e-18 (" << ref.rhs_evals
            << " evaluations for two solves), its error estimate " << std::setprecision(2) << ref.error_estimate
            << "\n";
  refs << name << ' ' << T;
  for (double v : x0) refs << ' ' << std::setprecision(17) << v;
  for (long double v : ref.x) refs << ' ' << std::setprecision(20) << v;
  refs << '\n';
  std::cout << std::setw(34) << std::left << "stepper" << std::right << std::setw(10) << "tol/dt" << std::setw(11)
            << "error" << std::setw(13) << "s/sim s" << std::setw(10) << "evals" << std::setw(9) << "steps"
            << std::setw(9) << "rejected" << std::setw(7) << "jac" << "\n";
  const int repeats = o.quick ? 3 : 5;
  const double min_sample = o.quick ? 5e-4 : 3e-3;
  auto add = [&](const std::string& stepper, const char* control, double tol, auto run) {
    X x = x0;
    auto left_out = [&](const std::string& why) {
      std::cout << std::setw(34) << std::left << stepper << std::right << std::setw(10) << std::setprecision(1)
                << tol << "  left out: " << why << "\n";
    };
    study::cost c;
    try {
      c = run(x);
    } catch (const std::exception& ex) {  // a NaN state ends in a singular mass matrix
      left_out(std::string("the run failed: ") + ex.what());
      return;
    }
    const double e = study::scaled_error(x, ref.x);
    if (!std::isfinite(e)) return left_out("the state is not finite (unstable)");
    if (e > 1) return left_out("error > 1, no accuracy at all");
    const double sec = study::median_seconds(
                           [&] {
                             X y = x0;
                             keep(run(y));
                             keep(y);
                           },
                           repeats, min_sample) /
                       T;
    out.push_back({name, stepper, control, tol, e, sec, c});
    std::cout << std::setw(34) << std::left << stepper << std::right << std::setprecision(1) << std::setw(10) << tol
              << std::setprecision(2) << std::setw(11) << e << std::setw(13) << sec << std::setw(10) << c.rhs_evals
              << std::setw(9) << c.steps << std::setw(9) << c.rejected << std::setw(7) << c.jacobian_evals << "\n";
  };

  std::vector<double> tols;
  for (int k = 3; k <= 12; k += o.quick ? 3 : 1) tols.push_back(std::pow(10.0, -k));
  auto controlled = [&](const char* stepper, auto make) {
    for (double tol : tols)
      add(stepper, "tol", tol, [&](X& x) { return study::integrate_controlled(make(tol), s, x, 0.0, T, 1e-3); });
  };
  controlled("runge_kutta_cash_karp54",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<X>()); });
  controlled("runge_kutta_dopri5",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<X>()); });
  controlled("runge_kutta_fehlberg78",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<X>()); });
  controlled("bulirsch_stoer", [](double tol) { return odeint::bulirsch_stoer<X>(tol, tol); });
  // rosenbrock4 with the exact Jacobian (dual numbers), and with central
  // differences in its place; the latter's evaluations include the 2·(n + 1)
  // of each Jacobian.
  auto stiff = [&](const char* stepper, auto method) {
    for (double tol : tols)
      add(stepper, "tol", tol, [&](X& x) {
        stiff_stats st;
        integrate_rosenbrock4<decltype(method)>(s, x, 0.0, T, 1e-3, tol, tol, nullptr, 0.0, &st);
        long evals = st.rhs_evals;
        if constexpr (std::is_same_v<decltype(method), jacobian_method::finite_difference>)
          evals += 2 * (S::n_state + 1) * st.jacobian_evals;
        return study::cost{evals, st.steps, st.jacobian_evals - st.steps, st.jacobian_evals};
      });
  };
  stiff("rosenbrock4 (exact Jacobian)", jacobian_method::exact{});
  stiff("rosenbrock4 (finite-difference Jacobian)", jacobian_method::finite_difference{});

  // Fixed steps: dt = T / n over a geometric sweep of n.
  auto fixed = [&](const char* stepper, auto make, double dt_max, double dt_min) {
    const double factor = o.quick ? 10.0 : std::sqrt(10.0);
    for (double dt = dt_max; dt >= dt_min * 0.999; dt /= factor) {
      const long n = std::max(1L, std::lround(T / dt));
      add(stepper, "dt", T / n, [&](X& x) { return study::integrate_fixed(make(), s, x, 0.0, T, n); });
    }
  };
  fixed("euler", [] { return odeint::euler<X>(); }, 1e-2, o.quick ? 1e-5 : 1e-6);
  fixed("runge_kutta4", [] { return odeint::runge_kutta4<X>(); }, 1e-1, 1e-4);
  fixed("adams_bashforth_moulton<5>", [] { return odeint::adams_bashforth_moulton<5, X>(); }, 1e-1, 1e-4);

  if constexpr (S::n_q == 1) {
    if (symplectic) {
      // H = p²/(2I) + V(q): with p = I·q̇, q̇ = p/I and ṗ = I·q̈(q). The scene's
      // q̈ does not depend on q̇ (one joint, no damping), so the derivative
      // at (q, 0) is the force. Positions q, "momenta" q̇ (I folded in).
      using Q = std::array<double, 1>;
      auto run_symplectic = [&](auto stepper, long n) {
        return [&s, stepper, n, T](X& x) mutable {
          study::cost c;
          Q q{x[0]}, p{x[1]};
          auto coordinate = [](const Q& pp, Q& dq) { dq[0] = pp[0]; };
          auto momentum = [&](const Q& qq, Q& dp) {
            ++c.rhs_evals;
            X y{qq[0], 0.0}, dy;
            s(y, dy, 0.0);
            dp[0] = dy[1];
          };
          const double dt = T / n;
          for (long i = 0; i < n; ++i)
            stepper.do_step(std::make_pair(coordinate, momentum), std::make_pair(std::ref(q), std::ref(p)), i * dt, dt);
          c.steps = n;
          x = X{q[0], p[0]};
          return c;
        };
      };
      auto sweep = [&](const char* stepper, auto make) {
        const double factor = o.quick ? 10.0 : std::sqrt(10.0);
        for (double dt = 1e-1; dt >= 1e-4 * 0.999; dt /= factor) {
          const long n = std::max(1L, std::lround(T / dt));
          add(stepper, "dt", T / n, run_symplectic(make(), n));
        }
      };
      sweep("symplectic_euler", [] { return odeint::symplectic_euler<Q>(); });
      sweep("symplectic_rkn_sb3a_mclachlan", [] { return odeint::symplectic_rkn_sb3a_mclachlan<Q>(); });
    }
  }
  if (!symplectic)
    std::cout << "symplectic steppers: not applicable, the Hamiltonian is not separable "
              << (S::n_v > 1 ? "(the mass matrix depends on q)" : "(velocity-dependent forces)") << "\n";
}

/// The scenes, in the order of the table: the paper's and chains, the free
/// body, the loop and the legged robot, then the contact scenes.
void study_chains(const options& o, std::vector<study::point>& points, std::ostream& refs);
void study_bodies(const options& o, std::vector<study::point>& points, std::ostream& refs);
void study_contact(const options& o, std::vector<study::point>& points, std::ostream& refs);

}  // namespace work_precision
