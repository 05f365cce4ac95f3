// flange::simulate: one checked call for a run. It must agree with the raw
// Odeint path where nothing goes wrong, and throw with the time, the state
// and the true reason where something does.
#include <boost/numeric/odeint.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include <flange/flange.hpp>
#include <flange/simulate/simulate.hpp>

using namespace flange;
using Catch::Matchers::Contains;
namespace odeint = boost::numeric::odeint;

TEST_CASE("simulate follows the arm's one-coordinate equation of motion and conserves its energy") {
  const models::robot_arm_params p;
  const auto arm = models::robot_arm(p);
  // (J_z + m·d²)·θ̈ = −m·g·d·cos θ (θ = 0 with the arm level), solved on its own at 1e-13.
  auto pendulum = [&](const std::array<double, 2>& s, std::array<double, 2>& ds, double) {
    ds[0] = s[1];
    ds[1] = -p.m * p.g * p.d * std::cos(s[0]) / (p.Jz + p.m * p.d * p.d);
  };
  std::array<double, 2> ref{1.0, 0.0};
  odeint::integrate_adaptive(odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<std::array<double, 2>>()),
                             pendulum, ref, 0.0, 10.0, 1e-3);
  const double E0 = recover(arm, 0.0, std::array<double, 2>{1.0, 0.0}).energy();
  double dE = 0;
  const auto x = simulate(arm, {1.0, 0.0}, 0.0, 10.0, {.tolerance = 1e-12}, [&](const auto& s, double t) {
    dE = std::max(dE, std::abs(recover(arm, t, s).energy() - E0) / std::abs(E0));
  });
  CHECK(std::abs(x[0] - ref[0]) < 1e-8);  // dopri5 at 1e-12 over ~7 periods: ~1e-9 measured
  CHECK(std::abs(x[1] - ref[1]) < 1e-8);
  CHECK(dE < 1e-9);
}

TEST_CASE("on a scene with nothing to project, simulate takes odeint::integrate_adaptive's steps, bit for bit") {
  // Neither loops nor quaternions: no projection and no reset of dopri5's
  // first-same-as-last derivative, so checking adds tests, not evaluations.
  const auto crane = models::gantry_crane({}, 0.7);
  using X = std::array<double, 4>;
  STATIC_REQUIRE(!detail::needs_projection<decltype(crane)>());
  const X x0{0.2, 0.4, 0.3, -0.5};
  budget b;
  X raw = x0;
  const std::size_t raw_steps = odeint::integrate_adaptive(
      odeint::make_controlled(1e-9, 1e-9, odeint::runge_kutta_dopri5<X>()), checked(crane, b), raw, 0.0, 3.0, 1e-3);
  std::size_t steps = 0;
  const X x = simulate(crane, x0, 0.0, 3.0, {.tolerance = 1e-9}, [&](const X&, double) { ++steps; });
  CHECK(steps == raw_steps + 1);  // the observer also sees the start
  for (int i = 0; i < 4; ++i) CHECK(x[i] == raw[i]);
  // A quaternion joint has something to project.
  const auto top = scene(World<"world">{}, Spherical<"ball">{}, Body<"b">({.m = 1, .J = Mat3d::Identity()}),
                         connect<"world.frame_b", "ball.frame_a">, connect<"ball.frame_b", "b.frame_a">);
  STATIC_REQUIRE(detail::needs_projection<decltype(top)>());
}

TEST_CASE("simulate keeps a loop closed") {
  const models::fourbar_params p;
  const auto fb = models::fourbar(p);
  auto x0 = initial_state<"crank_pivot", "crank_pin", "rocker_pin">(fb, {.q = 1.0, .v = 3.0}, {.q = 1.3}, {.q = 2.4});
  close_loops<"crank_pivot">(fb, x0);
  const double E0 = recover(fb, 0.0, x0).energy();
  const auto x = simulate(fb, x0, 0.0, 5.0, {.tolerance = 1e-12});
  CHECK(std::abs(recover(fb, 5.0, x).energy() - E0) / E0 < 1e-9);
  std::array<double, 3> zero{};
  const auto k = detail::loop_kinematics<decltype(fb)>(fb, x.data(), zero.data());
  CHECK(std::max(std::abs(k.phi[0]), std::abs(k.phi[1])) < 1e-12);
}

TEST_CASE("simulate throws with the time, the state and the true reason") {
  const auto arm = models::robot_arm();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SECTION("a NaN initial state") {
    CHECK_THROWS_WITH(simulate(arm, {nan, 0.0}, 0.0, 1.0),
                      Contains("the state is not finite at t = 0") && Contains("x = [nan"));
  }
  SECTION("an input that turns NaN") {
    const auto bad = models::robot_arm({}, [](double t) { return Vec3d(0, 0, t < 0.5 ? 0.0 : std::nan("")); });
    CHECK_THROWS_WITH(simulate(bad, {0.3, 0.0}, 0.0, 1.0), Contains("the derivative is not finite at t = 0.5"));
  }
  SECTION("a tolerance that double precision cannot meet") {
    CHECK_THROWS_WITH(simulate(arm, {0.3, 0.0}, 0.0, 1.0, {.tolerance = 0}),
                      Contains("tolerance 0 cannot be met in double precision"));
  }
  SECTION("a spent budget") {
    CHECK_THROWS_WITH(simulate(arm, {0.3, 0.0}, 0.0, 100.0, {.max_rhs_evals = 1000}),
                      Contains("the budget of 1000 derivative evaluations is spent"));
  }
  SECTION("a loop left open") {
    const auto fb = models::fourbar({});
    auto x0 = initial_state<"crank_pivot">(fb, {.q = 1.0});
    CHECK_THROWS_WITH(simulate(fb, x0, 0.0, 1.0), Contains("leaves the loop closed by Revolute \"rocker_pivot\" open"));
  }
}
