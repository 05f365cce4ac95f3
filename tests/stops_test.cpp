// Joint stops (axis_law::limited, Simbody's MobilityLinearStop) against
// Simbody on the same scenes, against the energy they store and dissipate,
// against the static rest on a stop, and through the residual.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/odeint.hpp>

#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "simbody/stops_scenes.hpp"

using namespace flange;
namespace ss = stops_scenes;

namespace {
const Mat3d J = Vec3d(ss::J[0], ss::J[1], ss::J[2]).asDiagonal();

/// A pendulum on a Revolute about z with the law Law (stops_scenes' numbers).
template <class Law = axis_law::limited<>>
auto pendulum(typename Revolute<"pin", axis::z, Law>::params p) {
  return scene(World<"world">{}, Revolute<"pin", axis::z, Law>(p), FixedTranslation<"rod">({.d = {ss::L, 0, 0}}),
               Body<"bob">({.m = ss::m, .J = J}), connect<"world.frame_b", "pin.frame_a">,
               connect<"pin.frame_b", "rod.frame_a">, connect<"rod.frame_b", "bob.frame_a">);
}
axis_stop pin_stop(double d = ss::pin_d) {
  return {.lower = ss::pin_lower, .upper = ss::pin_upper, .stiffness = ss::pin_k, .dissipation = d};
}
auto slider() {
  return scene(World<"world">{},
               Prismatic<"slide", axis::x, double, axis_law::limited<>>(
                   {.stop = {.lower = ss::slider_lower, .upper = ss::slider_upper, .stiffness = ss::slider_k,
                             .dissipation = ss::slider_d}}),
               Body<"block">({.m = ss::m, .J = J}), connect<"world.frame_b", "slide.frame_a">,
               connect<"slide.frame_b", "block.frame_a">);
}

/// The stop's generalized force, written out again from Simbody's documentation.
double simbody_stop(double q, double u, double lo, double hi, double k, double d) {
  if (q > hi) return std::min(0.0, -k * (q - hi) * (1 + d * u));
  if (q < lo) return std::max(0.0, -k * (q - lo) * (1 - d * u));
  return 0.0;
}
/// How far q is past a bound.
double past(double q, double lo, double hi) { return q > hi ? q - hi : q < lo ? q - lo : 0.0; }

/// dopri5 at 1e-12 from sample to sample.
template <class S, class X>
void advance(const S& s, X& x, double t0, double t1) {
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, t0, t1,
                             1e-4);
}
}  // namespace

#ifdef FLANGE_SIMBODY_STOPS
TEST_CASE("a pendulum and a slider against their stops follow Simbody's MobilityLinearStop") {
  // stops_reference.cpp wrote Simbody's trajectories: "scene t q u" rows.
  std::ifstream in(FLANGE_SIMBODY_STOPS);
  REQUIRE(in);
  std::map<std::string, std::vector<std::array<double, 3>>> ref;
  std::string name;
  double t, q, u;
  while (in >> name >> t >> q >> u) ref[name].push_back({t, q, u});
  REQUIRE(ref["pendulum"].size() == ss::samples + 1);
  REQUIRE(ref["slider"].size() == ss::samples + 1);
  auto compare = [](const auto& s, const std::vector<std::array<double, 3>>& rows, double q0, double u0) {
    using X = typename std::decay_t<decltype(s)>::state_type;
    X x{q0, u0};
    double worst = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (k > 0) advance(s, x, rows[k - 1][0], rows[k][0]);
      worst = std::max({worst, std::abs(x[0] - rows[k][1]), std::abs(x[1] - rows[k][2])});
    }
    return worst;
  };
  const double pendulum_error = compare(pendulum({.stop = pin_stop()}), ref["pendulum"], ss::pin_q0, ss::pin_u0);
  const double slider_error = compare(slider(), ref["slider"], ss::slider_q0, ss::slider_u0);
  INFO("largest difference from Simbody: pendulum " << pendulum_error << ", slider " << slider_error);
  // Both integrated at 1e-12 over impacts, rests and bounces: their
  // difference is the steppers' error through the stops' kinks.
  CHECK(pendulum_error < 1e-6);
  CHECK(slider_error < 1e-6);
  // The runs did reach the stops: the pendulum rests past its lower bound,
  // the block bounced off both.
  CHECK(ref["pendulum"].back()[1] < ss::pin_lower - 0.02);
  CHECK(ref["slider"][24][2] > 1.0);
  CHECK(ref["slider"][49][2] < -0.9);
}
#endif

TEST_CASE("a pendulum released onto a stop loses exactly the energy the stop dissipates, and satisfies its residual") {
  const auto s = pendulum({.stop = pin_stop()});
  using X = decltype(s)::state_type;
  // The stop's non-conservative power (τ_stop + k·x)·φ̇ integrated beside the
  // state: what the damping takes, and what is lost where the force would pull.
  using Y = std::array<double, 3>;
  auto augmented = [&](const Y& y, Y& dy, double t) {
    X x{y[0], y[1]}, dx;
    s(x, dx, t);
    const double tau = simbody_stop(y[0], y[1], ss::pin_lower, ss::pin_upper, ss::pin_k, ss::pin_d);
    dy = {dx[0], dx[1], -(tau + ss::pin_k * past(y[0], ss::pin_lower, ss::pin_upper)) * y[1]};
  };
  Y y{ss::pin_q0, ss::pin_u0, 0.0};
  const double E0 = recover(s, 0.0, X{y[0], y[1]}).energy();
  double worst_residual = 0, deepest = 0;
  for (int k = 1; k <= 300; ++k) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<Y>()), augmented, y,
                               0.01 * (k - 1), 0.01 * k, 1e-4);
    worst_residual = std::max(worst_residual, scaled_residual(s, recover(s, 0.01 * k, X{y[0], y[1]})));
    deepest = std::min(deepest, y[0] - ss::pin_lower);
  }
  const double E = recover(s, 3.0, X{y[0], y[1]}).energy();
  INFO("energy " << E0 << " -> " << E << ", dissipated " << y[2] << ", deepest " << deepest);
  CHECK(y[2] > 1.0);                                    // the stop did real work
  // Power balance, to the integration error relative to the energy the swing
  // exchanges (m·g·L; E0 itself is near the potential's arbitrary zero).
  CHECK(std::abs(E0 - E - y[2]) < 1e-9 * ss::m * ss::g * ss::L);
  CHECK(worst_residual < 1e-12);  // M₂·n = −stop(φ, φ̇) holds on the recovered variables
  CHECK(deepest < -0.05);         // it hit the stop hard
}

TEST_CASE("a stop without dissipation returns the energy it stores") {
  const auto s = pendulum({.stop = pin_stop(0.0)});
  using X = decltype(s)::state_type;
  X x{ss::pin_q0, ss::pin_u0};
  const double E0 = recover(s, 0.0, x).energy();  // near the potential's zero: drift is measured against m·g·L
  double drift = 0, deepest = 0;
  for (int k = 1; k <= 300; ++k) {
    advance(s, x, 0.01 * (k - 1), 0.01 * k);
    drift = std::max(drift, std::abs(recover(s, 0.01 * k, x).energy() - E0));
    deepest = std::min(deepest, x[0] - ss::pin_lower);
  }
  INFO("energy drift " << drift << ", deepest " << deepest);
  CHECK(drift < 1e-9 * ss::m * ss::g * ss::L);  // relative to the energy the swing exchanges
  CHECK(deepest < -0.05);
}

TEST_CASE("a pendulum comes to rest on its stop at the static penetration") {
  // At rest: k·x = m·g·L·cos(φ) with x = lower − φ, solved by Newton.
  const auto s = pendulum({.stop = pin_stop(2.0)});
  using X = decltype(s)::state_type;
  X x{ss::pin_q0, 0.0};
  advance(s, x, 0.0, 30.0);
  double phi = ss::pin_lower;
  for (int i = 0; i < 50; ++i) {
    const double r = ss::pin_k * (ss::pin_lower - phi) - ss::m * ss::g * ss::L * std::cos(phi);
    const double dr = -ss::pin_k + ss::m * ss::g * ss::L * std::sin(phi);
    phi -= r / dr;
  }
  INFO("rest " << x[0] << " vs static " << phi);
  CHECK(std::abs(x[1]) < 1e-8);
  CHECK(std::abs(x[0] - phi) < 1e-8);
  CHECK(phi < ss::pin_lower - 0.02);  // a real penetration, not the bound itself
}

TEST_CASE("stops combine with a joint's friction and spring-damper laws") {
  // Past the upper bound the generalized force is the law's plus the stop's.
  const double d = 0.3, fc = 0.2, vs = 0.05, c = 4.0, phi0 = 0.2;
  const auto f = pendulum<axis_law::limited<axis_law::friction>>({.d = d, .f_c = fc, .v_s = vs, .stop = pin_stop()});
  const auto sd = pendulum<axis_law::limited<axis_law::spring_damper>>({.c = c, .d = d, .phi0 = phi0, .stop = pin_stop()});
  const auto free = pendulum<axis_law::none>({});
  using X = decltype(free)::state_type;
  const double I = J(2, 2) + ss::m * ss::L * ss::L;
  for (double q : {-0.7, -0.4, 0.3, 1.0, 1.3}) {
    for (double u : {-2.0, 0.1, 3.0}) {
      X x{q, u}, a, b, g;
      f(x, a, 0.0);
      sd(x, b, 0.0);
      free(x, g, 0.0);
      const double stop = simbody_stop(q, u, ss::pin_lower, ss::pin_upper, ss::pin_k, ss::pin_d);
      CHECK(a[1] == Approx(g[1] + (stop - d * u - fc * std::tanh(u / vs)) / I).epsilon(1e-13));
      CHECK(b[1] == Approx(g[1] + (stop - c * (q - phi0) - d * u) / I).epsilon(1e-13));
    }
  }
  // Energy: the spring's and the stop's potentials both counted.
  const X x{1.2, 0.0};
  const double x_past = 1.2 - ss::pin_upper;
  CHECK(recover(sd, 0.0, x).energy() - recover(free, 0.0, x).energy() ==
        Approx(0.5 * c * (1.2 - phi0) * (1.2 - phi0) + 0.5 * ss::pin_k * x_past * x_past).epsilon(1e-13));
}

TEST_CASE("stop parameters are checked at construction") {
  using Limited = Revolute<"knee", axis::z, axis_law::limited<>>;
  CHECK_THROWS_WITH(Limited({.stop = {.lower = 1.0, .upper = -1.0, .stiffness = 10}}),
                    Catch::Contains("Revolute \"knee\": stop lower = 1 is above upper = -1"));
  CHECK_THROWS_WITH(Limited({.stop = {.lower = -1.0, .upper = 1.0, .stiffness = -10}}),
                    Catch::Contains("Revolute \"knee\": stop stiffness = -10") && Catch::Contains("must not be negative"));
  CHECK_THROWS_WITH(Limited({.stop = {.lower = std::nan(""), .upper = 1.0, .stiffness = 10}}),
                    Catch::Contains("Revolute \"knee\": stop bounds lower = nan"));
  CHECK_THROWS_WITH((Prismatic<"rail", axis::x, double, axis_law::limited<>>(
                        {.stop = {.lower = 0, .upper = 1, .stiffness = 10, .dissipation = std::nan("")}})),
                    Catch::Contains("Prismatic \"rail\": parameter stop dissipation is not finite"));
  // An infinite bound has no stop: a one-sided stop is legal.
  CHECK_NOTHROW(Limited({.stop = {.upper = 1.0, .stiffness = 10}}));
}

TEST_CASE("every joint with its parameters defaulted constructs with {}") {
  // Prismatic and Revolute alike (the stops default to none: infinite bounds).
  CHECK(Prismatic<"p", axis::x>{}.n() == Vec3d::UnitX());
  CHECK(Revolute<"r", axis::y>{}.n() == Vec3d::UnitY());
  CHECK_NOTHROW(Revolute<"r", axis::y, axis_law::limited<>>{});
}
