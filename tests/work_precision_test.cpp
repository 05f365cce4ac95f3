// The work-precision study's measuring tools (flange/study/work_precision.hpp)
// on a problem with a known solution: a torsional oscillator, a flange scene
// whose joint spring gives I·φ̈ = −c·φ with c = I, so φ = cos t exactly.
// No timing is asserted here; benchmarks/work_precision.cpp does the timing.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>
#include <flange/study/work_precision.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

using namespace flange;

namespace {
constexpr double I = 0.02 + 1.0 * 0.25;  // J_z + m·l², folded the same way by the scene
auto oscillator() {
  return scene(World<"world", gravity_kind::none>{},
               Revolute<"joint", axis::z, axis_law::spring_damper>({.c = I, .d = 0.0, .phi0 = 0.0}),
               FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
               Body<"mass">({.m = 1.0, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">);
}
using X = decltype(oscillator())::state_type;
constexpr double T = 10.0;
const X x0{1.0, 0.0};
std::array<long double, 2> exact(long double t) { return {std::cos(t), -std::sin(t)}; }
}  // namespace

TEST_CASE("the scaled error is max |x − r| / (1 + |r|), and infinite for a non-finite state") {
  CHECK(study::scaled_error(std::array<double, 2>{1.0, 2.0}, std::array<double, 2>{1.5, -1.0}) == Approx(1.5));
  CHECK(study::scaled_error(std::array<double, 2>{1.0, 0.0}, std::array<double, 2>{1.0, 1e-3}) ==
        Approx(1e-3 / (1 + 1e-3)));
  CHECK(study::scaled_error(std::array<double, 2>{1.0, 1e6 + 1.0}, std::array<double, 2>{1.0, 1e6}) ==
        Approx(1.0 / (1e6 + 1)));
  CHECK(std::isinf(study::scaled_error(std::array<double, 2>{std::nan(""), 0.0}, std::array<double, 2>{0, 0})));
}

TEST_CASE("the long-double reference is within its own error estimate of the exact solution") {
  const auto s = oscillator();
  const auto ref = study::long_double_reference(s, x0, T);
  const double actual = study::scaled_error(ref.x, exact(T));
  INFO("actual " << actual << ", estimate " << ref.error_estimate);
  // The estimate (the 1e-17 solve against the 1e-18 one) bounds the 1e-18
  // solve's error, and both are far below the 1e-12 a double solve can reach.
  CHECK(actual <= ref.error_estimate);
  CHECK(ref.error_estimate < 1e-13);
  CHECK(actual < 1e-15);
}

TEST_CASE("fixed-step steppers: counted evaluations, and the error falls at the method's order") {
  const auto s = oscillator();
  auto run = [&](auto stepper, long n, study::cost& c) {
    X x = x0;
    c = study::integrate_fixed(stepper, s, x, 0.0, T, n);
    return study::scaled_error(x, exact(T));
  };
  study::cost c;
  // Euler, order 1: halving the step halves the error.
  const double e1 = run(odeint::euler<X>(), 20000, c);
  CHECK(c.rhs_evals == 20000);
  CHECK(c.steps == 20000);
  const double e2 = run(odeint::euler<X>(), 40000, c);
  CHECK(e1 / e2 == Approx(2.0).epsilon(0.05));
  // RK4, order 4: halving the step divides the error by 16, four evaluations a step.
  const double r1 = run(odeint::runge_kutta4<X>(), 200, c);
  CHECK(c.rhs_evals == 800);
  const double r2 = run(odeint::runge_kutta4<X>(), 400, c);
  CHECK(r1 / r2 == Approx(16.0).epsilon(0.05));
  // Adams–Bashforth–Moulton (5 steps, predictor–corrector): two evaluations a
  // step once started, and an error falling faster than RK4's.
  const double a1 = run(odeint::adams_bashforth_moulton<5, X>(), 400, c);
  const double a2 = run(odeint::adams_bashforth_moulton<5, X>(), 800, c);
  INFO("ABM errors " << a1 << " " << a2 << ", evaluations " << c.rhs_evals);
  CHECK(a1 / a2 > 16.0);
  CHECK(c.rhs_evals < 2 * 800 + 4 * 5);
}

TEST_CASE("controlled steppers: the error falls as the tolerance tightens, and the counts add up") {
  const auto s = oscillator();
  auto sweep = [&](const char* name, auto make, long evals_per_attempt, long extra) {
    double previous = 1.0;
    for (double tol : {1e-4, 1e-7, 1e-10}) {
      X x = x0;
      const auto c = study::integrate_controlled(make(tol), s, x, 0.0, T, 1e-3);
      const double e = study::scaled_error(x, exact(T));
      INFO(name << " at " << tol << ": error " << e << ", " << c.steps << " steps, " << c.rejected
                << " rejected, " << c.rhs_evals << " evaluations");
      CHECK(e < previous);
      // Local error control: the global error over 1.6 periods stays within a
      // modest multiple of the tolerance.
      CHECK(e < 100 * tol);
      if (evals_per_attempt > 0) CHECK(c.rhs_evals == evals_per_attempt * (c.steps + c.rejected) + extra);
      previous = e;
    }
  };
  // Each attempt evaluates the derivative at its start, then its stages.
  sweep("cash_karp54", [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<X>()); },
        6, 0);
  // dopri5 is first-same-as-last: the first derivative once, then 6 stages.
  sweep("dopri5", [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<X>()); }, 6, 1);
  sweep("fehlberg78", [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<X>()); },
        13, 0);
  sweep("bulirsch_stoer", [](double tol) { return odeint::bulirsch_stoer<X>(tol, tol); }, 0, 0);
}

TEST_CASE("rosenbrock4: the error falls as the tolerance tightens, and each attempt costs one Jacobian") {
  const auto s = oscillator();
  double previous = 1.0;
  for (double tol : {1e-4, 1e-7, 1e-10}) {
    X x = x0;
    stiff_stats st;
    integrate_rosenbrock4(s, x, 0.0, T, 1e-3, tol, tol, nullptr, 0.0, &st);
    const double e = study::scaled_error(x, exact(T));
    INFO("tolerance " << tol << ": error " << e << ", " << st.steps << " steps, " << st.jacobian_evals
                      << " Jacobians, " << st.rhs_evals << " evaluations");
    CHECK(e < previous);
    CHECK(e < 100 * tol);
    CHECK(st.jacobian_evals >= st.steps);
    CHECK(st.rhs_evals == 6 * st.jacobian_evals);  // Odeint's rosenbrock4: 6 stages, one Jacobian per attempt
    previous = e;
  }
}

TEST_CASE("the cheapest point in a band") {
  std::vector<study::point> pts{{"a", "x", "tol", 1e-3, 1e-4, 2.0, {}},
                                {"a", "y", "tol", 1e-6, 1e-7, 3.0, {}},
                                {"a", "z", "tol", 1e-6, 5e-7, 1.0, {}},
                                {"b", "w", "tol", 1e-6, 1e-9, 0.5, {}}};
  CHECK(study::cheapest(pts, "a", 1e-3)->stepper == "z");
  CHECK(study::cheapest(pts, "a", 1e-6)->stepper == "z");
  CHECK(study::cheapest(pts, "a", 2e-7)->stepper == "y");
  CHECK(study::cheapest(pts, "a", 1e-9) == nullptr);
}
