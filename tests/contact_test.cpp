// Contact (forces/contact.hpp): a ball thrown onto the ground against
// Simbody's HuntCrossleyForce on the same scene; bounces without dissipation
// back to the drop height; the restitution against Hunt–Crossley's relation;
// a ball rolling and sliding down an incline against the rigid-body closed
// forms; the residual on the recovered variables; bad parameters.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/odeint.hpp>

#include <fstream>
#include <numbers>
#include <vector>

#include "simbody/free_body_rows.hpp"

using namespace flange;
namespace cs = contact_scenes;

namespace {
using Ground = Contact<"ball_ground", contact_shape::sphere, contact_shape::half_space>;

contact_material material(double dissipation = cs::dissipation, double mu_s = cs::static_friction,
                          double mu_d = cs::dynamic_friction, double mu_v = cs::viscous_friction) {
  return {.stiffness = cs::stiffness, .dissipation = dissipation, .static_friction = mu_s, .dynamic_friction = mu_d,
          .viscous_friction = mu_v};
}

/// A ball of radius cs::radius on a FreeMotion above the half-space n·p ≤ 0.
template <class Gravity = gravity_kind::uniform>
auto ball(const contact_material& m, const Vec3d& n = Vec3d::UnitY(), double vt = cs::transition_velocity) {
  return scene(World<"world", Gravity>{}, FreeMotion<"fly">{},
               Body<"ball">({.m = cs::m, .J = Vec3d(cs::J[0], cs::J[1], cs::J[2]).asDiagonal()}),
               Ground({.a = {.radius = cs::radius}, .b = {.n = n}, .material_a = m, .material_b = m,
                       .transition_velocity = vt}),
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "ball.frame_a">,
               connect<"fly.frame_b", "ball_ground.frame_a">, connect<"world.frame_b", "ball_ground.frame_b">);
}
using Ball = decltype(ball(material()));
using X = Ball::state_type;

/// The state: centre r, identity orientation, velocity v, ω (body axes).
X start(const Vec3d& r, const Vec3d& v, const Vec3d& w = Vec3d::Zero()) {
  X x{};
  for (int i = 0; i < 3; ++i) {
    x[i] = r[i];
    x[7 + i] = v[i];
    x[10 + i] = w[i];
  }
  x[6] = 1;
  return x;
}
}  // namespace

#ifdef FLANGE_SIMBODY_CONTACT
TEST_CASE("a ball thrown onto the ground follows Simbody's HuntCrossleyForce") {
  // contact_reference.cpp wrote Simbody's trajectories (the ball's first), in flange's state layout.
  const auto rows = cs::read_block(FLANGE_SIMBODY_CONTACT, 0);
  REQUIRE(rows.size() == cs::samples + 1);
  const auto s = ball(material());
  X last{};
  const auto c =
      cs::compare(s, start({0, cs::y0, 0}, {cs::vx0, cs::vy0, cs::vz0}, {cs::wx0, 0, cs::wz0}), rows, last);
  INFO("largest difference from Simbody " << c.worst << ", residual " << c.worst_residual << ", lowest centre "
                                           << c.lowest);
  // Both integrated at 1e-12 through impacts, sliding and rolling.
  CHECK(c.worst < 1e-6);
  CHECK(c.worst_residual < 1e-12);
  CHECK(c.lowest < cs::radius);  // it did touch the ground
  // And it ends rolling on the ground: in contact, its contact point
  // slipping slower than the friction's transition speed.
  const auto end = recover(s, rows.back()[0], last);
  CHECK(end.internal<"ball_ground", "δ">() > 0);
  CHECK(end.internal<"ball_ground", "v_s">() < cs::transition_velocity);
}
#endif

TEST_CASE("a ball without dissipation or friction bounces back to its drop height, ten times") {
  const auto s = ball(material(0, 0, 0, 0));
  const double h = 0.3;
  X x = start({0, h, 0}, {0, 0, 0});
  const double E0 = recover(s, 0.0, x).energy();
  std::vector<double> apex;
  double t = 0, prev_vy = 0, drift = 0, lowest = 1;
  const double dt = 1e-4;
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>());
  while (apex.size() < 10) {
    odeint::integrate_adaptive(stepper, s, x, t, t + dt, dt);
    t += dt;
    if (prev_vy > 0 && x[8] <= 0) apex.push_back(x[1]);  // v_y turned: the top of a bounce (within g·dt²/8)
    prev_vy = x[8];
    lowest = std::min(lowest, x[1]);
    if (apex.size() % 3 == 0) drift = std::max(drift, std::abs(recover(s, t, x).energy() - E0));
  }
  double worst = 0;
  for (double y : apex) worst = std::max(worst, std::abs(y - h) / h);
  INFO("10 bounces over " << t << " s: apex heights within " << worst << " of the drop height; energy drift "
                          << drift << " J; deepest penetration " << cs::radius - lowest << " m");
  CHECK(worst < 1e-6);
  CHECK(drift < 1e-9 * E0);
  CHECK(lowest < cs::radius);
}

TEST_CASE("with dissipation the restitution is Hunt and Crossley's 1 − c·v for small impact speeds") {
  // Frictionless, without gravity (which acts during the impact, ~10 ms at
  // these speeds): the speed after the impact over the speed before.
  // e = 1 − c·v to first order in c·v (Hunt and Crossley 1975; Simbody's
  // HuntCrossleyForce documentation).
  for (double c : {0.02, 0.05}) {
    const auto s = ball<gravity_kind::none>(material(c, 0, 0, 0));
    const double v0 = 0.5;
    X x = start({0, cs::radius + 0.001, 0}, {0, -v0, 0});
    const double v_in = v0;
    // Until it leaves the ground again.
    double t = 0;
    auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>());
    while (!(x[1] > cs::radius && x[8] > 0)) {
      odeint::integrate_adaptive(stepper, s, x, t, t + 1e-5, 1e-5);
      t += 1e-5;
    }
    const double e = x[8] / v_in, cv = c * v_in;
    INFO("c = " << c << ": e = " << e << " against 1 − c·v = " << 1 - cv);
    CHECK(std::abs(e - (1 - cv)) < cv * cv);  // second order in c·v
  }
}

TEST_CASE("a ball on an incline rolls at (5/7)·g·sin θ when friction holds, and slides at g·(sin θ − μ·cos θ) when it cannot") {
  const double theta = 20 * std::numbers::pi / 180;
  // The static penetration under the ball's weight across the slope (same
  // material on both sides: k = E^(2/3)/2, f = (4/3)·k·δ·√(R·k·δ)).
  const double k = std::cbrt(cs::stiffness * cs::stiffness) / 2;
  const double depth =
      std::pow(3 * cs::m * cs::g * std::cos(theta) / (4 * k * std::sqrt(cs::radius * k)), 2.0 / 3.0);
  auto accel = [&](double mu) {
    const Vec3d n(-std::sin(theta), std::cos(theta), 0);  // the incline's outward normal; downhill is −x
    const auto s = ball(material(0.5, mu, mu, 0), n, 1e-4);
    // At rest on the incline, at the static penetration; measured over 0.5 s
    // after 0.2 s of settling.
    X x = start((cs::radius - depth) * n, Vec3d::Zero());
    const Vec3d down(-std::cos(theta), -std::sin(theta), 0);
    auto speed = [&](const X& y) { return down.dot(Vec3d(y[7], y[8], y[9])); };
    x = simulate(s, x, 0.0, 0.2, {.tolerance = 1e-10});
    const double v1 = speed(x);
    x = simulate(s, x, 0.2, 0.7, {.tolerance = 1e-10});
    return (speed(x) - v1) / 0.5;
  };
  const double roll = accel(0.8), slide = accel(0.05);
  const double g_sin = cs::g * std::sin(theta);
  // Rolling: tan θ = 0.36 < (7/2)·0.8. It rolls on the contact point, in
  // the middle of the overlap: on the radius r = R − δ/2, so that
  // a = g·sin θ/(1 + J/(m·r²)), (5/7)·g·sin θ for a rigid ball (J = (2/5)·m·R²).
  // The regularised friction lets it creep at a steady v_t·(the friction
  // it needs)/(μ·f_n), which does not change a.
  const double r = cs::radius - depth / 2;
  const double rolling = g_sin / (1 + cs::J[2] / (cs::m * r * r));
  const double sliding = cs::g * (std::sin(theta) - 0.05 * std::cos(theta));
  INFO("rolling " << roll << " against " << rolling << " ((5/7)·g·sin θ = " << 5.0 / 7 * g_sin << "); sliding "
                  << slide << " against " << sliding);
  CHECK(std::abs(roll - rolling) < 1e-8 * g_sin);
  CHECK(std::abs(roll - 5.0 / 7 * g_sin) < 1e-3 * g_sin);
  // Sliding: tan θ = 0.36 > (7/2)·0.05, slipping far above v_t, so f_t = μ·f_n.
  CHECK(std::abs(slide - sliding) < 1e-8 * g_sin);
}

TEST_CASE("contact parameters are checked at construction") {
  const auto m = material();
  CHECK_THROWS_WITH(Ground({.a = {.radius = -0.5}, .material_a = m, .material_b = m}),
                    Catch::Contains("Contact \"ball_ground\": a.radius = -0.5 must be positive"));
  CHECK_THROWS_WITH(Ground({.a = {.radius = 0.1}, .b = {.n = {0, 2, 0}}, .material_a = m, .material_b = m}),
                    Catch::Contains("Contact \"ball_ground\": b.n = [0 2 0] is not a unit vector (norm 2)"));
  CHECK_THROWS_WITH(Ground({.a = {.radius = 0.1}, .b = {.n = {0, 0, 0}}, .material_a = m, .material_b = m}),
                    Catch::Contains("is not a unit vector"));
  auto bad = m;
  bad.static_friction = -0.5;
  CHECK_THROWS_WITH(Ground({.a = {.radius = 0.1}, .material_a = bad, .material_b = m}),
                    Catch::Contains("Contact \"ball_ground\": material_a.static_friction = -0.5 must be finite and not negative"));
  bad = m;
  bad.stiffness = std::nan("");
  CHECK_THROWS_WITH(Ground({.a = {.radius = 0.1}, .material_a = m, .material_b = bad}),
                    Catch::Contains("material_b.stiffness = nan"));
  CHECK_THROWS_WITH(Ground({.a = {.radius = 0.1}, .material_a = m, .material_b = m, .transition_velocity = 0}),
                    Catch::Contains("transition_velocity = 0 must be positive"));
}

TEST_CASE("two spheres collide head-on: momentum kept, and without dissipation equal masses swap their velocities") {
  // No gravity; ball a moves at 1 m/s toward ball b at rest, offset sideways
  // by nothing (head-on) or by a little (glancing: momentum still kept).
  auto balls = [](double c) {
    const contact_material m{.stiffness = 1e7, .dissipation = c, .static_friction = 0.5, .dynamic_friction = 0.4};
    const Mat3d J = Mat3d::Identity() * 0.004;
    return scene(World<"world", gravity_kind::none>{}, FreeMotion<"fa">{}, Body<"a">({.m = 1.0, .J = J}),
                 FreeMotion<"fb">{}, Body<"b">({.m = 1.0, .J = J}),
                 Contact<"hit", contact_shape::sphere, contact_shape::sphere>(
                     {.a = {.radius = 0.1}, .b = {.radius = 0.1}, .material_a = m, .material_b = m}),
                 connect<"world.frame_b", "fa.frame_a">, connect<"fa.frame_b", "a.frame_a">,
                 connect<"world.frame_b", "fb.frame_a">, connect<"fb.frame_b", "b.frame_a">,
                 connect<"fa.frame_b", "hit.frame_a">, connect<"fb.frame_b", "hit.frame_b">);
  };
  for (double c : {0.0, 0.5}) {
    for (double offset : {0.0, 0.05}) {
      const auto s = balls(c);
      using Y = decltype(s)::state_type;
      Y x{};
      x[0] = -0.3;  // a's centre
      x[6] = 1;
      x[8] = offset;  // b's centre: (0, offset, 0)
      x[13] = 1;
      x[14] = 1.0;  // a's velocity along x
      const auto p0 = momentum(s, x);
      x = simulate(s, x, 0.0, 0.6, {.tolerance = 1e-12});
      const auto p1 = momentum(s, x);
      INFO("c = " << c << ", offset " << offset << ": a's velocity " << x[14] << ", b's " << x[20]);
      CHECK((p1.linear - p0.linear).norm() < 1e-10);
      CHECK((p1.angular - p0.angular).norm() < 1e-10);
      if (c == 0 && offset == 0) {  // an elastic head-on collision of equal masses
        CHECK(std::abs(x[14]) < 1e-6);
        CHECK(std::abs(x[20] - 1.0) < 1e-6);
      }
    }
  }
}
