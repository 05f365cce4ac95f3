// bodies(scene) and momentum(scene, x): the bodies as the scene declares
// them, and the momentum against its conservation laws (a free body, a
// torque-free floating tree with joint springs inside it), against
// dp/dt = M·g under gravity, and against the single body's closed form.
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>
#include <flange/flange.hpp>

using namespace flange;

namespace {
/// A floating base (FreeMotion) with two arms on sprung, damped revolutes
/// about different axes and an offset centre of mass: internal forces only,
/// and gravity g.
auto floating_tree(double g) {
  return scene(World<"world">({.g = {0, 0, -g}}), FreeMotion<"base_joint">{},
               Body<"base", cm::offset>({.m = 3.0, .J = Vec3d(0.2, 0.3, 0.4).asDiagonal(), .r_cm = {0.05, 0, 0}}),
               Revolute<"hip", axis::y, axis_law::spring_damper>({.c = 40, .d = 0.5, .phi0 = 0.3}),
               FixedTranslation<"thigh_len">({.d = {0, 0, -0.4}}),
               Body<"thigh", cm::offset>({.m = 1.0, .J = Vec3d(0.02, 0.02, 0.001).asDiagonal(), .r_cm = {0, 0, -0.2}}),
               Revolute<"twist", axis::any, axis_law::spring_damper>({.n = {1, 1, 0}, .c = 5, .d = 0.1}),
               Body<"wheel">({.m = 0.5, .J = Vec3d(0.01, 0.01, 0.02).asDiagonal()}),
               connect<"world.frame_b", "base_joint.frame_a">, connect<"base_joint.frame_b", "base.frame_a">,
               connect<"base.frame_a", "hip.frame_a">, connect<"hip.frame_b", "thigh_len.frame_a">,
               connect<"thigh_len.frame_a", "thigh.frame_a">, connect<"thigh_len.frame_b", "twist.frame_a">,
               connect<"twist.frame_b", "wheel.frame_a">);
}
template <class S>
typename S::state_type tumbling(const S& s) {
  auto x = initial_state<"hip", "twist">(s, {.q = -0.4, .v = 3.0}, {.q = 0.2, .v = -5.0});
  set_joint<"base_joint">(s, x, {.r = {0.1, -0.2, 1.0}, .v = {0.3, 0.1, 2.0}, .R = orientation::cardan(0.3, -0.2, 0.5),
                                 .w = {1.0, -2.0, 0.5}});
  return x;
}
}  // namespace

TEST_CASE("bodies(scene) lists every body with its mass, centre of mass and inertia") {
  const auto s = floating_tree(9.81);
  const auto b = bodies(s);
  REQUIRE(b.size() == 3);
  CHECK(b[0].name == "base");
  CHECK(b[0].m == 3.0);
  CHECK(b[0].r_cm == Vec3d(0.05, 0, 0));
  CHECK(b[0].J(2, 2) == 0.4);
  CHECK(b[1].name == "thigh");
  CHECK(b[2].name == "wheel");
  CHECK(b[2].r_cm == Vec3d::Zero());
}

TEST_CASE("a single free body's momentum is its closed form") {
  const auto s = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"fly">{},
                       Body<"b", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.1, 0, 0}}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">);
  auto x = neutral_state(s);
  const Mat3d R = orientation::cardan(0.3, -0.2, 0.5).R;  // frame_b → world is Rᵀ in flange's convention
  const Vec3d r(1, 2, 3), v(0.5, -1, 2), w(1, -2, 0.5);
  set_joint<"fly">(s, x, {.r = r, .v = v, .R = orientation::matrix(R), .w = w});
  const auto h = momentum(s, x);
  const Vec3d cm = r + R.transpose() * Vec3d(0.1, 0, 0);
  const Vec3d vcm = v + R.transpose() * w.cross(Vec3d(0.1, 0, 0));
  const Vec3d L = cm.cross(2.0 * vcm) + R.transpose() * (Vec3d(0.1, 0.2, 0.3).asDiagonal() * w);
  CHECK((h.linear - 2.0 * vcm).norm() < 1e-14);
  CHECK((h.angular - L).norm() < 1e-14);
}

TEST_CASE("a torque-free floating tree keeps its momentum, and under gravity p grows by M·g·t") {
  const double t1 = 2.0;
  SECTION("no gravity: linear and angular momentum conserved to the stepper's error") {
    const auto s = floating_tree(0.0);
    const auto x0 = tumbling(s);
    const auto h0 = momentum(s, x0);
    REQUIRE(h0.linear.norm() > 1);
    REQUIRE(h0.angular.norm() > 1);
    const auto run = simulate(s, x0, output_times(0.0, t1, 0.1), {.tolerance = 1e-12});
    double worst = 0;
    for (const auto& x : run.x) {
      const auto h = momentum(s, x);
      worst = std::max({worst, (h.linear - h0.linear).norm(), (h.angular - h0.angular).norm()});
    }
    // Each step's error within 1e-12·(1 + |x|) (|x| ≤ ~10), over run.steps
    // steps: the bound the method gives (measured: 4.5e-13 over 2,294 steps;
    // a momentum that left out a body's spin or turned it the wrong way
    // would be off by more than 0.1).
    CHECK(worst < static_cast<double>(run.steps) * 1.1e-11);
    // The energy is not conserved (the joints are damped): the momentum is a
    // law of its own, not a consequence of a conserved energy.
    CHECK(energy(s, t1, run.x.back()).total() < energy(s, 0.0, x0).total() - 1e-3);
  }
  SECTION("gravity: p(t) − p(0) = M·g·t") {
    const double g = 9.81, M = 4.5;
    const auto s = floating_tree(g);
    const auto x0 = tumbling(s);
    const auto x1 = simulate(s, x0, 0.0, t1, {.tolerance = 1e-12});
    const Vec3d dp = momentum(s, x1).linear - momentum(s, x0).linear;
    CHECK((dp - Vec3d(0, 0, -M * g * t1)).norm() < 1e-8);  // measured: 2.6e-13
  }
}

namespace {
/// The centre of mass of what joint C carries, in frame_a coordinates
/// relative to frame_a's origin, at the coordinates of x.
template <int C, class S, class State>
Vec3d carried_cm_in_frame_a(const S& s, const State& x) {
  const detail::frames_at_state<S, double> at(s, x);
  const auto c = detail::momentum_of(s, at, [](int i) { return detail::carried_by<S, C>(i); });
  const auto& a = at.frames[S::table.frame_base[C]];
  return a.R * (c.first_moment / c.m - a.r);
}
/// Its velocity by central differences along q̇ (the derivative's first half).
template <int C, class S>
Vec3d carried_cm_velocity_fd(const S& s, const typename S::state_type& x) {
  typename S::state_type dx, xp = x, xm = x;
  s(x, dx, 0.0);
  const double h = 1e-5;
  for (int i = 0; i < S::n_q; ++i) xp[i] += h * dx[i], xm[i] -= h * dx[i];
  return (carried_cm_in_frame_a<C>(s, xp) - carried_cm_in_frame_a<C>(s, xm)) / (2 * h);
}
}  // namespace

TEST_CASE("a free body set by its centre-of-mass velocity moves its centre of mass so") {
  const auto s = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"fly">{},
                       Body<"b", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.3, -0.2, 0.1}}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">);
  const Mat3d R = orientation::cardan(0.3, -0.2, 0.5).R;
  const Vec3d w(1, -2, 0.5), v_cm(0.5, -1, 2), r_cm(0.3, -0.2, 0.1);
  const auto x = initial_state<"fly">(s, {.r = {1, 2, 3}, .R = orientation::matrix(R), .w = w, .v_cm = v_cm});
  // Closed form: frame_b's velocity is the centre of mass's less ω × (its offset), in world axes (Rᵀ).
  const Vec3d v = get_joint<"fly">(s, x).v;
  CHECK((v - (v_cm - R.transpose() * w.cross(r_cm))).norm() < 1e-15);
  CHECK((momentum(s, x).linear / 2.0 - v_cm).norm() < 1e-15);
  CHECK(get_joint<"fly">(s, x).w == w);
  // Both velocities at once are refused, naming the joint.
  auto y = x;
  CHECK_THROWS_WITH(set_joint<"fly">(s, y, {.v = {1, 0, 0}, .v_cm = v_cm}),
                    Catch::Contains("\"fly\"") && Catch::Contains("not both"));
  CHECK_THROWS_WITH(set_joint<"fly">(s, y, {.v_cm = Vec3d(0, NAN, 0)}), Catch::Contains("v_cm is not finite"));
}

TEST_CASE("a centre-of-mass velocity for a joint that carries no mass is refused, naming the joint") {
  // "probe" carries only a frame; the body hangs from the world through its own joint
  const auto s = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"probe">{},
                       FixedTranslation<"tip">({.d = {0.1, 0, 0}}), FreeMotion<"fly">{},
                       Body<"b">({.m = 1.0, .J = Mat3d::Identity()}), connect<"world.frame_b", "probe.frame_a">,
                       connect<"probe.frame_b", "tip.frame_a">, connect<"world.frame_b", "fly.frame_a">,
                       connect<"fly.frame_b", "b.frame_a">);
  CHECK_THROWS_WITH((initial_state<"probe">(s, {.v_cm = Vec3d(1, 0, 0)})),
                    Catch::Contains("FreeMotion \"probe\"") && Catch::Contains("carries no mass"));
  // the other joint, which carries the body, takes one
  const auto x = initial_state<"fly">(s, {.v_cm = Vec3d(1, 0, 0)});
  CHECK((momentum(s, x).linear - Vec3d(1, 0, 0)).norm() < 1e-15);
}

TEST_CASE("a floating tree set by its centre-of-mass velocity: the whole tree's, with the joints' rates as given") {
  const auto s = floating_tree(9.81);
  const Vec3d v_cm(0.4, -0.3, 1.5), w(0.7, 0.2, -1.1);
  const auto R = orientation::cardan(0.2, 0.1, -0.4);
  // In either order: the centre-of-mass velocity is worked out after every joint's rate is written.
  const auto x = initial_state<"base_joint", "hip", "twist">(s, {.r = {0, 0, 1}, .R = R, .w = w, .v_cm = v_cm},
                                                            {.q = -0.4, .v = 3.0}, {.q = 0.2, .v = -5.0});
  const auto y = initial_state<"hip", "base_joint", "twist">(s, {.q = -0.4, .v = 3.0},
                                                            {.r = {0, 0, 1}, .R = R, .w = w, .v_cm = v_cm},
                                                            {.q = 0.2, .v = -5.0});
  CHECK(x == y);
  CHECK((momentum(s, x).linear / 4.5 - v_cm).norm() < 1e-14);
  // Against the centre of mass's motion by central differences (error about h² = 1e-10).
  constexpr int C = decltype(s)::index_of("base_joint");
  CHECK((carried_cm_velocity_fd<C>(s, x) - v_cm).norm() < 1e-8);
}

TEST_CASE("a free motion on a turning frame: v_cm is relative to frame_a, in its axes") {
  const auto s = scene(World<"world">({.g = {0, 0, 0}}), Revolute<"spin", axis::any>({.n = {0.3, 0, 1}}),
                       FixedTranslation<"arm">({.d = {0.5, 0.2, 0}}), FreeMotion<"fly">{},
                       Body<"hub">({.m = 1.0, .J = Mat3d::Identity()}),
                       Body<"b", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.3, -0.2, 0.1}}),
                       connect<"world.frame_b", "spin.frame_a">, connect<"spin.frame_b", "arm.frame_a">,
                       connect<"spin.frame_b", "hub.frame_a">, connect<"arm.frame_b", "fly.frame_a">,
                       connect<"fly.frame_b", "b.frame_a">);
  const Vec3d v_cm(0.2, 0.7, -0.5);
  const auto x = initial_state<"spin", "fly">(
      s, {.q = 0.6, .v = 2.5},
      {.r = {0.1, 0.2, 0.3}, .R = orientation::cardan(0.5, 0.4, -0.3), .w = {0.3, -0.6, 0.9}, .v_cm = v_cm});
  constexpr int C = decltype(s)::index_of("fly");
  CHECK((carried_cm_velocity_fd<C>(s, x) - v_cm).norm() < 1e-8);
}
