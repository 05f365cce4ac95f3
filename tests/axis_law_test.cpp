// A revolute joint with a spring-damper on its axis: against the exact damped
// oscillator, through the residual, and stiff (c = 1e9), where rosenbrock4
// with the exact Jacobian finishes in a bounded number of steps and an
// explicit stepper fails loudly (a step-count limit), never quietly.
#include <vector>

#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/checked.hpp>
#include <flange/simulate/odeint.hpp>
#include <flange/simulate/rosenbrock4.hpp>

#include "consistency.hpp"

using namespace flange;

namespace {
// No gravity: the arm is a torsional oscillator I·φ̈ + d·φ̇ + c·(φ − φ0) = 0
// with I = J_z + m·l² about the joint.
auto oscillator(double c, double d, double phi0) {
  return scene(World<"world", gravity_kind::none>{},
               Revolute<"joint", axis::z, axis_law::spring_damper>({.c = c, .d = d, .phi0 = phi0}),
               FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
               Body<"mass">({.m = 1.0, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">);
}
constexpr double I = 0.02 + 1.0 * 0.25;
}  // namespace

TEST_CASE("a joint spring-damper is the exact damped oscillator") {
  const double c = 4.0, d = 0.3, phi0 = 0.2;
  const auto s = oscillator(c, d, phi0);
  using X = decltype(s)::state_type;
  // Underdamped: φ − φ0 = e^{−ζω t}·(A cos ω_d t + B sin ω_d t).
  const double w = std::sqrt(c / I), zeta = d / (2 * std::sqrt(c * I)), wd = w * std::sqrt(1 - zeta * zeta);
  const double A = 1.0 - phi0, B = (0.5 + zeta * w * A) / wd;  // φ(0) = 1, φ̇(0) = 0.5
  X x{1.0, 0.5};
  double worst = 0, worst_residual = 0;
  test::consistency along;
  odeint::integrate_const(odeint::make_dense_output(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, 10.0,
                          0.1, record(s, [&](const auto& sol) {
                            const double t = sol.t;
                            const double exact = phi0 + std::exp(-zeta * w * t) * (A * std::cos(wd * t) + B * std::sin(wd * t));
                            worst = std::max(worst, std::abs(sol.q[0] - exact));
                            worst_residual = std::max(worst_residual, scaled_residual(s, sol));
                            along.sample(s, t, X{sol.q[0], sol.v[0]});
                          }));
  CHECK(along.orthogonality <= 1e-12);
  CHECK(along.algorithms <= 1e-10);
  INFO("worst error " << worst << ", worst scaled residual " << worst_residual);
  // dopri5 at 1e-12 over ≈ 4 periods: the global error stays near 1e-11.
  CHECK(worst < 1e-9);
  CHECK(worst_residual < 1e-12);
}

TEST_CASE("a stiff joint spring (c = 1e9): rosenbrock4 settles in few steps, dopri5 is stopped loudly",
          "[hard]") {
  const double c = 1e9, phi0 = 0.2;
  const double d = 2 * std::sqrt(c * I);  // critically damped: time constant 1/ω ≈ 1.6e-5 s
  const auto s = oscillator(c, d, phi0);
  using X = decltype(s)::state_type;
  // rosenbrock4 with the exact Jacobian: A-stable, its step grows once the
  // fast transient has died, and it reaches the rest angle.
  X x{1.0, 0.0};
  const std::size_t steps = integrate_rosenbrock4(s, x, 0.0, 1.0, 1e-6, 1e-8, 1e-8);
  INFO("rosenbrock4: " << steps << " steps, final φ = " << x[0] << ", φ̇ = " << x[1]);
  CHECK(steps < 500);
  test::consistency along;
  along.sample(s, 1.0, x);
  CHECK(along.orthogonality <= 1e-12);
  CHECK(along.residual <= 1e-9);
  CHECK(along.algorithms <= 1e-10);
  CHECK(std::abs(x[0] - phi0) < 1e-8);
  CHECK(std::abs(x[1]) < 1e-6);
  // An explicit stepper must stay below its stability limit h ≈ 3.3/ω ≈ 5e-5 s:
  // dopri5 needs about 18 600 steps (over 110 000 evaluations) for this second,
  // against rosenbrock4's 408. A budget stops it with an exception, with the
  // time and state, instead of a silent crawl.
  // Every explicit stepper: how many evaluations it needs for this second,
  // and that a budget below that stops it loudly. (Fixed-step RK4 at a step
  // above its stability limit blows up instead; the checked system reports
  // the non-finite state.)
  struct row {
    const char* name;
    long evals;
  };
  std::vector<row> table;
  auto survey = [&](const char* name, auto&& integrate) {
    budget unlimited;
    X z{1.0, 0.0};
    integrate(checked(s, unlimited), z);
    table.push_back({name, unlimited.rhs_evals});
    CHECK(std::abs(z[0] - phi0) < 1e-6);  // they do get there, at a price
    budget limited{.max_rhs_evals = 20000};
    X w{1.0, 0.0};
    CHECK_THROWS_AS(integrate(checked(s, limited), w), simulation_error);
  };
  survey("runge_kutta_cash_karp54", [](auto sys, X& z) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_cash_karp54<X>()), sys, z, 0.0,
                               1.0, 1e-6);
  });
  survey("runge_kutta_dopri5", [](auto sys, X& z) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<X>()), sys, z, 0.0, 1.0,
                               1e-6);
  });
  survey("runge_kutta_fehlberg78", [](auto sys, X& z) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_fehlberg78<X>()), sys, z, 0.0,
                               1.0, 1e-6);
  });
  survey("bulirsch_stoer", [](auto sys, X& z) {
    odeint::bulirsch_stoer<X> bs(1e-8, 1e-8);
    odeint::integrate_adaptive(bs, sys, z, 0.0, 1.0, 1e-6);
  });
  for (const auto& r : table) UNSCOPED_INFO(r.name << ": " << r.evals << " evaluations (rosenbrock4: " << steps << " steps)");
  {
    budget b;
    X z{1.0, 0.0};
    CHECK_THROWS_WITH(odeint::integrate_const(odeint::runge_kutta4<X>(), checked(s, b), z, 0.0, 1.0, 1e-4),
                      Catch::Matchers::Contains("not finite"));
  }
  CHECK(table.size() == 4);
  X y{1.0, 0.0};
  budget b{.max_rhs_evals = 20000};
  CHECK_THROWS_WITH(odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<X>()),
                                               checked(s, b), y, 0.0, 1.0, 1e-6),
                    Catch::Matchers::Contains("budget of 20000 derivative evaluations") &&
                        Catch::Matchers::Contains("t = ") && Catch::Matchers::Contains("x = ["));
}

TEST_CASE("a joint spring-damper refuses negative or non-finite coefficients") {
  using J = Revolute<"knee", axis::z, axis_law::spring_damper>;
  CHECK_THROWS_WITH(J({.c = -1.0}), Catch::Matchers::Contains("Revolute \"knee\"") &&
                                        Catch::Matchers::Contains("c = -1"));
  CHECK_THROWS_WITH(J({.d = std::nan("")}), Catch::Matchers::Contains("Revolute \"knee\"") &&
                                                Catch::Matchers::Contains("d (damping)"));
}

TEST_CASE("a checked system turns a NaN into an error with time and state") {
  // An input that breaks down at t = 0.5: without the check the trajectory
  // would fill with NaN.
  auto bad = [](double t) { return t < 0.5 ? 1.0 : std::nan(""); };
  const auto crane = models::gantry_crane({}, bad);
  using X = decltype(crane)::state_type;
  X x{0.0, -1.0, 0.0, 0.0};
  budget b;
  try {
    odeint::integrate_const(odeint::runge_kutta4<X>(), checked(crane, b), x, 0.0, 1.0, 0.01);
    FAIL("no error");
  } catch (const simulation_error& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("derivative is not finite") && Catch::Matchers::Contains("x = ["));
    CHECK(e.time >= 0.5);
    CHECK(e.time < 0.52);
  }
  CHECK(b.rhs_evals > 0);
}

TEST_CASE("energy includes joint springs: ½·c·(q − q0)² for a revolute and a prismatic spring-damper") {
  // The case: c = 100, φ0 = 0.5, at φ = 0: 12.5 J.
  const auto s = oscillator(100.0, 0.3, 0.5);
  const auto sol = recover(s, 0.0, std::array<double, 2>{0.0, 0.0});
  CHECK(sol.elastic_potential == Approx(12.5).epsilon(1e-15));
  CHECK(sol.energy() == Approx(12.5).epsilon(1e-15));
  const auto rail = scene(World<"world", gravity_kind::none>{},
                          Prismatic<"rail", axis::x, double, axis_law::spring_damper>({.c = 8, .d = 0.4, .s0 = 0.3}),
                          Body<"cart">({.m = 2.0}), connect<"world.frame_b", "rail.frame_a">,
                          connect<"rail.frame_b", "cart.frame_a">);
  const auto r = recover(rail, 0.0, std::array<double, 2>{1.3, 0.5});
  CHECK(r.elastic_potential == Approx(0.5 * 8 * 1.0).epsilon(1e-15));
  CHECK(r.energy() == Approx(4.0 + 0.5 * 2.0 * 0.25).epsilon(1e-15));
}

TEST_CASE("power balance with joint springs: energy + dissipated work = input work") {
  // The arm under gravity with a spring-damper on its joint and a motor torque
  // M(t): the energy (kinetic + gravity + spring) changes by the motor's work
  // minus the damper's. The two works are integrated with the motion, as
  // extra states, so the balance holds to the integrator's tolerance.
  const double c = 100, d = 0.3, phi0 = 0.5;
  auto motor = [](auto t) { return Vec3d(0, 0, 2 * std::sin(3 * static_cast<double>(t))); };
  const auto s = scene(World<"world">{}, Revolute<"joint", axis::z, axis_law::spring_damper>({.c = c, .d = d, .phi0 = phi0}),
                       torque<"motor">(motor), FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
                       Body<"mass">({.m = 1.0, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
                       connect<"world.frame_b", "joint.frame_a">, connect<"world.frame_b", "motor.frame_a">,
                       connect<"joint.frame_b", "rod.frame_a">, connect<"joint.frame_b", "motor.frame_b">,
                       connect<"rod.frame_b", "mass.frame_a">);
  using X = std::array<double, 4>;  // φ, φ̇, input work, dissipated work
  auto augmented = [&](const X& x, X& dx, double t) {
    std::array<double, 2> y{x[0], x[1]}, dy;
    s(y, dy, t);
    dx[0] = dy[0];
    dx[1] = dy[1];
    dx[2] = motor(t)(2) * x[1];
    dx[3] = d * x[1] * x[1];
  };
  X x{-1.0, 0.5, 0.0, 0.0};
  const double e0 = recover(s, 0.0, std::array<double, 2>{x[0], x[1]}).energy();
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), augmented, x, 0.0,
                             5.0, 1e-3);
  const auto end = recover(s, 5.0, std::array<double, 2>{x[0], x[1]});
  const double gap = end.energy() - e0 + x[3] - x[2];
  INFO("energy " << e0 << " -> " << end.energy() << " (spring " << end.elastic_potential << "), input work " << x[2]
                 << ", dissipated " << x[3] << ": balance off by " << gap);
  // dopri5 at 1e-12 over 5 s on states of order 10: global error ~1e-10.
  CHECK(std::abs(gap) < 1e-8);
  CHECK(end.elastic_potential > 0);
}
