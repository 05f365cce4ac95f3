// Hard cases for closed loops (ctest -L hard): a parallelogram four-bar
// through a thousand singular positions, and a loop made stiff by a joint
// spring, stepped by rosenbrock4 with its exact Jacobian.
#include <boost/numeric/odeint.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>

using namespace flange;
namespace odeint = boost::numeric::odeint;
using X6 = std::array<double, 6>;
constexpr double pi = std::numbers::pi;

TEST_CASE("a parallelogram four-bar passes 1000 flat singular positions without blow-up", "[hard]") {
  models::fourbar_params p;
  p.ground = p.coupler = 1.0;
  p.crank = p.rocker = 0.3;
  auto fb = models::fourbar(p);
  const double th0 = 0.3, w0 = 12.0;
  const auto q = models::fourbar_coordinates(p, th0, th0);
  X6 x{q[0], q[1], q[2], w0, -w0, w0};
  const double E0 = recover(fb, 0.0, x).energy();
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
  double dE = 0, coupler = 0;
  int flat = 0;
  double t = 0;
  while (flat < 1000) {
    const double before = x[0];
    integrate_projected(stepper, fb, x, t, t + 1.0, 1e-3);
    t += 1.0;
    dE = std::max(dE, std::abs(recover(fb, 0.0, x).energy() - E0) / E0);
    coupler = std::max(coupler, std::abs(std::remainder(x[0] + x[1], 2 * pi)));
    flat += int(std::floor(x[0] / pi) - std::floor(before / pi));
    REQUIRE(t < 400);  // about 3.9 flat positions a second
  }
  // 4.2e-10 after 78 flat positions (loops_test); the energy error is a sum
  // over the passages, so about 13 times that after 1000.
  CHECK(dE < 1e-7);
  CHECK(coupler < 1e-9);  // still a parallelogram: it never switched branch
}

TEST_CASE("a four-bar made stiff by a joint spring: rosenbrock4 settles it, dopri5 is stopped loudly", "[hard]") {
  // A spring-damper of c = 1e6 N m/rad on the coupler's pin, critically
  // damped on the pin's own inertia scale: the loop's one degree of freedom
  // rings at ~1e3 rad/s and dies within milliseconds, then the mechanism
  // rests where the spring balances gravity.
  const models::fourbar_params p;
  using models::bar;
  const double th2 = 1.0;
  const auto q = models::fourbar_coordinates(p, th2, models::freudenstein_rocker(p, th2));
  auto fb = scene(World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
                  Revolute<"crank_pin", axis::z, axis_law::spring_damper>({.c = 1e6, .d = 2e3, .phi0 = q[1] + 0.01}),
                  bar<"coupler">(p.coupler, p.m_coupler), Revolute<"rocker_pin", axis::z>{},
                  bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
                  Revolute<"rocker_pivot", axis::z>{},
                  connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
                  connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
                  connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
                  connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "rocker_pivot.frame_a">,
                  connect<"rocker.frame_b", "rocker_pivot.frame_b">);
  X6 x{q[0], q[1], q[2], 0, 0, 0};
  close_loops<"crank_pivot">(fb, x);
  X6 x0 = x;
  stiff_stats st;
  integrate_rosenbrock4(fb, x, 0.0, 0.5, 1e-4, 1e-8, 1e-8, nullptr, 0.0, &st);
  CHECK(st.steps < 2000);
  // At rest: no rate, no acceleration, the loop closed.
  X6 dx;
  fb(x, dx, 0.5);
  for (int i = 3; i < 6; ++i) {
    CHECK(std::abs(x[i]) < 1e-6);
    CHECK(std::abs(dx[i]) < 1e-4);
  }
  std::array<double, 3> zero{};
  const auto k = detail::loop_kinematics<decltype(fb)>(fb, x.data(), zero.data());
  CHECK(std::max(std::abs(k.phi[0]), std::abs(k.phi[1])) < 1e-8);
  // The spring holds the coupler's pin near its rest angle against gravity.
  CHECK(std::abs(x[1] - (q[1] + 0.01)) < 1e-3);

  budget b{.max_rhs_evals = 20000};
  auto dopri = odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<X6>());
  CHECK_THROWS_WITH(odeint::integrate_adaptive(dopri, checked(fb, b), x0, 0.0, 0.5, 1e-4),
                    Catch::Contains("budget of 20000 derivative evaluations is spent"));
}
