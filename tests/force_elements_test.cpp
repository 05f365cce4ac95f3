// Force elements between frames (Spring, Damper, SpringDamper) and from the
// World (WorldForce, WorldTorque): against closed forms, a conservation law,
// the residual of their own equations, and the second algorithm.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/odeint.hpp>

#include "consistency.hpp"
#include "random_params.hpp"

using namespace flange;

namespace {
constexpr double m = 2.0, c = 50.0, s0 = 0.5;

/// A mass on a rail along x, tied to the World's origin by a line force: with
/// s > 0 the line is the rail, so m·s̈ = −c·(s − s₀) − d·ṡ.
template <class Element>
auto rail_with(Element e) {
  return scene(World<"world", gravity_kind::none>{}, Prismatic<"rail", axis::x>({}), PointMass<"cart">({.m = m}),
               std::move(e), connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
               connect<"world.frame_b", "spring.frame_a">, connect<"rail.frame_b", "spring.frame_b">);
}

template <class S>
std::array<double, S::n_state> integrate(const S& s, std::array<double, S::n_state> x, double T) {
  using X = std::array<double, S::n_state>;
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, T, 1e-3);
  return x;
}

/// The paper's arm (horizontal at φ = 0) with one more component and its connections.
template <class... Extra>
auto arm_with(Extra... extra) {
  return scene(World<"world">{}, Revolute<"joint", axis::z>{}, FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
               Body<"mass">({.m = 1.0, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">, extra...);
}
constexpr double I = 0.02 + 0.25;  // J_z + m·d²
}  // namespace

TEST_CASE("a mass on a spring oscillates about the unstretched length") {
  const auto s = rail_with(Spring<"spring">({.c = c, .s0 = s0}));
  const double w = std::sqrt(c / m), T = 3.0;
  const auto x = integrate(s, {1.0, 0.0}, T);
  // dopri5 at 1e-12 over ~15 periods: global error below 1e-9.
  CHECK(std::abs(x[0] - (s0 + 0.5 * std::cos(w * T))) < 1e-9);
  CHECK(std::abs(x[1] - (-0.5 * w * std::sin(w * T))) < 1e-9);
}

TEST_CASE("a spring-damper is the exact damped oscillator, a damper alone decays the rate") {
  const double d = 3.0, T = 2.0;
  const auto s = rail_with(SpringDamper<"spring">({.c = c, .s0 = s0, .d = d}));
  const double w = std::sqrt(c / m), zeta = d / (2 * std::sqrt(c * m)), wd = w * std::sqrt(1 - zeta * zeta);
  const double A = 0.5, B = zeta * w * A / wd;  // s(0) − s₀ = 0.5, ṡ(0) = 0
  const auto x = integrate(s, {1.0, 0.0}, T);
  CHECK(std::abs(x[0] - (s0 + std::exp(-zeta * w * T) * (A * std::cos(wd * T) + B * std::sin(wd * T)))) < 1e-9);

  const auto damper = rail_with(Damper<"spring">({.d = d}));
  const auto y = integrate(damper, {1.0, 2.0}, T);  // ṡ = 2·e^{−d t / m}, while s stays positive
  CHECK(std::abs(y[1] - 2.0 * std::exp(-d * T / m)) < 1e-10);
  CHECK(std::abs(y[0] - (1.0 + 2.0 * m / d * (1 - std::exp(-d * T / m)))) < 1e-9);
}

TEST_CASE("a pendulum on a spring conserves kinetic, gravity and spring energy, and satisfies its residual") {
  // The spring's anchor sits off the plane of motion, so its force has a
  // component along the joint axis: the planar algorithm must drop exactly that.
  const auto s = arm_with(FixedTranslation<"post">({.d = {0.3, 0.4, 0.1}}), Spring<"spring">({.c = 20.0, .s0 = 0.2}),
                          connect<"world.frame_b", "post.frame_a">, connect<"post.frame_b", "spring.frame_a">,
                          connect<"rod.frame_b", "spring.frame_b">);
  using X = decltype(s)::state_type;
  X x{-0.4, 1.0};
  const double E0 = recover(s, 0.0, x).energy();
  test::consistency along;
  double drift = 0;
  odeint::integrate_const(odeint::make_dense_output(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, 5.0,
                          0.1, record(s, [&](const auto& sol) {
                            drift = std::max(drift, std::abs(sol.energy() - E0));
                            along.sample(s, sol.t, X{sol.q[0], sol.v[0]});
                          }));
  INFO("energy " << E0 << ", drift " << drift);
  CHECK(drift < 1e-9 * std::abs(E0));  // tolerance 1e-12 per step, ~10³ steps
  CHECK(along.residual < 1e-12);       // s² = |r₂ − r₁|², f = c·(s − s₀), s·F = ∓f·R·(r₂ − r₁)
  CHECK(along.algorithms < 1e-10);     // articulated-body with the same external forces
  CHECK(along.samples == 51);
}

TEST_CASE("line forces between links of a spatial chain: planar, spatial and articulated-body agree") {
  std::mt19937 rng(9);
  auto p = test::chain_params<3>(rng);
  for (auto& a : p.axis) a = Vec3d::UnitZ();
  const auto planar = scene(World<"world">{}, Revolute<"j0", axis::z>{}, FixedTranslation<"r0">({.d = p.d[0]}),
                            Body<"b0">({.m = p.m[0], .J = p.J[0]}), Revolute<"j1", axis::z>{},
                            FixedTranslation<"r1">({.d = p.d[1]}), Body<"b1">({.m = p.m[1], .J = p.J[1]}),
                            SpringDamper<"sd">({.c = 30.0, .s0 = 0.1, .d = 0.7}),
                            connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "r0.frame_a">,
                            connect<"r0.frame_b", "b0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
                            connect<"j1.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">,
                            connect<"j0.frame_b", "sd.frame_a">, connect<"r1.frame_b", "sd.frame_b">);
  for (int k = 0; k < 20; ++k) {
    std::array<double, 2> q{test::uniform(rng, -2, 2), test::uniform(rng, -2, 2)}, qd{test::uniform(rng, -2, 2),
                                                                                        test::uniform(rng, -2, 2)};
    std::array<double, 2> a, b, c3;
    accelerations_planar(planar, 0.0, q.data(), qd.data(), a.data());
    accelerations_newton_euler(planar, 0.0, q.data(), qd.data(), b.data());
    accelerations_articulated_body(planar, 0.0, q.data(), qd.data(), c3.data());
    for (int i = 0; i < 2; ++i) {
      CHECK(std::abs(a[i] - b[i]) < 1e-11 * (1 + std::abs(b[i])));
      CHECK(std::abs(c3[i] - b[i]) < 1e-10 * (1 + std::abs(b[i])));
    }
    CHECK(scaled_residual(planar, recover(planar, 0.0, std::array<double, 4>{q[0], q[1], qd[0], qd[1]})) < 1e-12);
  }
}

TEST_CASE("a world force and a world torque add their moments about the joint") {
  // (J_z + m·d²)·φ̈ = −m·g·d·cos φ + (r × F)_z + τ_z, r = d·(cos φ, sin φ, 0).
  const Vec3d F(1.5, -0.7, 0.4), tau(0.2, -0.3, 0.9);
  const auto world = arm_with(WorldForce<"push">({.value = F}), WorldTorque<"twist">({.value = tau}),
                              connect<"rod.frame_b", "push.frame_b">, connect<"rod.frame_b", "twist.frame_b">);
  // Resolved in the body's frame: a force along the rod has no moment.
  const auto along_rod = arm_with(WorldForce<"push", Vec3d, resolve::frame_b>({.value = Vec3d(3.0, 0, 0)}),
                                  connect<"rod.frame_b", "push.frame_b">);
  const auto plain = arm_with();
  std::mt19937 rng(2);
  for (int k = 0; k < 50; ++k) {
    const std::array<double, 2> x{test::uniform(rng, -3, 3), test::uniform(rng, -3, 3)};
    std::array<double, 2> a, b, p;
    world(x, a, 0.0);
    along_rod(x, b, 0.0);
    plain(x, p, 0.0);
    const double phi = x[0], d = 0.5, g = 9.81;
    const double expected = (-1.0 * g * d * std::cos(phi) + d * std::cos(phi) * F.y() - d * std::sin(phi) * F.x() + tau.z()) / I;
    CHECK(std::abs(a[1] - expected) < 1e-13 * (1 + std::abs(expected)));
    CHECK(std::abs(b[1] - p[1]) < 1e-13 * (1 + std::abs(p[1])));
    CHECK(scaled_residual(world, recover(world, 0.0, x)) < 1e-13);
    CHECK(scaled_residual(along_rod, recover(along_rod, 0.0, x)) < 1e-13);
  }
}

TEST_CASE("force elements check their parameters, and a line force fails loudly where its ends meet") {
  CHECK_THROWS_WITH(Spring<"spring">({.c = -1.0}), Catch::Contains("Spring \"spring\": stiffness c = -1 is negative"));
  CHECK_THROWS_WITH(Spring<"spring">({.c = 1.0, .s0 = -0.5}),
                    Catch::Contains("Spring \"spring\": unstretched length s0 = -0.5 is negative"));
  CHECK_THROWS_WITH(Damper<"damper">({.d = std::nan("")}),
                    Catch::Contains("Damper \"damper\": parameter d (damping) is not finite"));
  CHECK_THROWS_WITH(WorldForce<"push">({.value = Vec3d(1, std::nan(""), 0)}),
                    Catch::Contains("WorldForce \"push\": parameter f_ext is not finite"));
  const auto s = rail_with(Spring<"spring">({.c = c, .s0 = s0}));
  std::array<double, 2> x{0.0, 1.0}, dx;
  CHECK_THROWS_WITH(s(x, dx, 0.25), Catch::Contains("Spring \"spring\": the two frames meet at t = 0.25"));
}
