// The analytic Jacobian (dynamics/derivatives.hpp) of scenes with balls, a
// Spherical or a FreeMotion whose rotation rates are the link's ω: against the
// dual-number Jacobian of the same scene and central differences
// (jacobian_agree.hpp), on a free body, a ball under and over other joints,
// floating quadrupeds with drives that read the state and with feet pressing
// into the ground (contact loads in every direction, the base's quaternion
// among them), a ball pressing into the ground (its link on the World's);
// and that a ball connected the other way round takes dual
// numbers.
#include <catch2/catch.hpp>

#include <flange/models/ball.hpp>
#include <flange/models/legged.hpp>
#include <flange/simulate/jacobian.hpp>

#include "jacobian_agree.hpp"

using namespace flange;
using test::agree;
using test::agree_at;

TEST_CASE("a free body's analytic Jacobian: the quaternion's rows and columns") {
  std::mt19937 rng(4901);
  const auto s = scene(World<"world">({.g = {0.4, -9.81, 1.2}}), FreeMotion<"base">{},
                       Body<"b", cm::offset>({.m = 2.0, .J = test::random_inertia(rng), .r_cm = {0.1, 0.2, -0.05}}),
                       connect<"world.frame_b", "base.frame_a">, connect<"base.frame_b", "b.frame_a">);
  STATIC_REQUIRE(detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(s)>>());
  agree(s, rng);
  // Far from the World's origin: the passes run about the base.
  auto x = test::random_state(s, rng);
  x[0] = 40, x[1] = -25, x[2] = 60;
  agree_at(s, x);
}

TEST_CASE("balls among one-axis joints: a Spherical under a FreeMotion, a FreeMotion under a Revolute") {
  std::mt19937 rng(4902);
  const auto a = scene(
      World<"world">({.g = {0, 0, -9.81}}), FixedTranslation<"post">({.d = {0.2, -0.1, 0.5}}), Spherical<"ball">{},
      Body<"b", cm::offset>({.m = 2.0, .J = test::random_inertia(rng), .r_cm = {0.1, 0.2, -0.05}}),
      FixedTranslation<"rod">({.d = {0.3, 0.1, -0.2}}), Revolute<"elbow", axis::y>{},
      Body<"c", cm::offset>({.m = 1.0, .J = test::random_inertia(rng), .r_cm = {0.3, 0, 0}}),
      Prismatic<"slide", axis::x>{}, Body<"d">({.m = 0.5, .J = test::random_inertia(rng)}),
      connect<"world.frame_b", "post.frame_a">, connect<"post.frame_b", "ball.frame_a">,
      connect<"ball.frame_b", "b.frame_a">, connect<"b.frame_a", "rod.frame_a">, connect<"rod.frame_b", "elbow.frame_a">,
      connect<"elbow.frame_b", "c.frame_a">, connect<"b.frame_a", "slide.frame_a">, connect<"slide.frame_b", "d.frame_a">);
  agree(a, rng);
  const auto b = scene(
      World<"world">({.g = {0, -9.81, 0}}), Revolute<"turntable", axis::y>{},
      Body<"table">({.m = 3.0, .J = test::random_inertia(rng)}), FixedTranslation<"arm">({.d = {0.5, 0.2, 0}}),
      FreeMotion<"puck">{}, Body<"p", cm::offset>({.m = 0.7, .J = test::random_inertia(rng), .r_cm = {0, 0.05, 0.1}}),
      Spherical<"hinge">{}, FixedTranslation<"stick">({.d = {0, -0.3, 0}}),
      Body<"bob", cm::offset>({.m = 0.2, .J = test::random_inertia(rng), .r_cm = {0, -0.2, 0}}),
      connect<"world.frame_b", "turntable.frame_a">, connect<"turntable.frame_b", "table.frame_a">,
      connect<"table.frame_a", "arm.frame_a">, connect<"arm.frame_b", "puck.frame_a">,
      connect<"puck.frame_b", "p.frame_a">, connect<"p.frame_a", "hinge.frame_a">,
      connect<"hinge.frame_b", "stick.frame_a">, connect<"stick.frame_b", "bob.frame_a">);
  agree(b, rng);
  // Connected frame_b toward the World a Spherical's ω is not its link's:
  // dual numbers.
  const auto reversed =
      scene(World<"world">{}, Spherical<"ball">{}, Body<"b">({.m = 1.0, .J = test::random_inertia(rng)}),
            connect<"world.frame_b", "ball.frame_b">, connect<"ball.frame_a", "b.frame_a">);
  STATIC_REQUIRE(!detail::analytic_derivatives<std::remove_cvref_t<decltype(reversed)>>());
}

TEST_CASE("floating quadrupeds: drives that read the state, feet on the ground") {
  std::mt19937 rng(4903);
  agree(models::legged<4, 1>(), rng);
  agree(models::legged<4, 2>({}, models::crouch_drive{}), rng);
  // Feet 1 cm into the ground (docs/contact.md's quadruped), the trunk
  // turned a little and every rate small and random: all four contacts press
  // and slip. Not against central differences: friction that peaks at a
  // slip of 1 mm/s and 1e7 N/m^1.5 contacts are not smooth on the scale of
  // their step (6e-6), where they are off by 1e-6 of the largest entry.
  const auto feet = models::legged<4, 3, true>({}, models::crouch_drive{});
  using S = std::remove_cvref_t<decltype(feet)>;
  STATIC_REQUIRE(detail::jacobian_takes_analytic<S>());
  for (int k = 0; k < 3; ++k) {
    auto x = models::crouched_state(feet);
    x[1] -= 0.05;  // the feet touch the ground at 0.04
    const double a = test::uniform(rng, -0.01, 0.01);  // about the vertical
    x[3 + 1] = std::sin(a / 2), x[3 + 3] = std::cos(a / 2);
    for (int i = S::n_q; i < S::n_state; ++i) x[i] = test::uniform(rng, -0.1, 0.1);
    // The same state 5 cm higher, off the ground: the feet's contacts change
    // the trunk's acceleration by tens of m/s².
    std::array<double, S::n_state> xs, f, f_off;
    std::copy(x.begin(), x.end(), xs.begin());
    feet(xs, f, 0.0);
    xs[1] += 0.05;
    feet(xs, f_off, 0.0);
    INFO("the trunk's vertical acceleration " << f[S::n_q + 1] << " on the ground, " << f_off[S::n_q + 1] << " off it");
    CHECK(std::abs(f[S::n_q + 1] - f_off[S::n_q + 1]) > 10);
    agree_at(feet, x, 0.0, k, false);
  }
}

TEST_CASE("a ball rolling and slipping 1 mm into the ground: the contact's loads in its link's lanes") {
  // The FreeMotion's link hangs from the World, where the half-space's loads
  // read the link's pose a scalar at a time (dynamics/external.hpp). Turned,
  // spinning, sliding: friction and the normal force both change with every
  // coordinate and rate. Not against central differences (friction peaks at
  // a slip of 1 mm/s, as for the quadruped's feet).
  const auto ball = models::ball_on_ground();
  using S = std::remove_cvref_t<decltype(ball)>;
  std::mt19937 rng(3307);
  for (int k = 0; k < 3; ++k) {
    std::array<double, S::n_state> x{};
    x[1] = 0.099 + test::uniform(rng, -0.0005, 0.0005);  // a radius of 0.1: 0.5–1.5 mm into the ground
    x[0] = test::uniform(rng, -1, 1), x[2] = test::uniform(rng, -1, 1);
    const Vec3d axis = Vec3d(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1)).normalized();
    const double a = test::uniform(rng, 0, 3);
    x[6] = std::cos(a / 2);  // the quaternion: (x, y, z, w)
    for (int i = 0; i < 3; ++i) x[3 + i] = std::sin(a / 2) * axis[i];
    for (int i = S::n_q; i < S::n_state; ++i) x[i] = test::uniform(rng, -2, 2);
    x[S::n_q + 1] = test::uniform(rng, -0.01, 0.01);  // pressing, not bouncing
    // The same state off the ground: the contact changes the vertical
    // acceleration by about g.
    std::array<double, S::n_state> f, f_off, xs = x;
    ball(xs, f, 0.0);
    xs[1] += 0.01;
    ball(xs, f_off, 0.0);
    INFO("the ball's vertical acceleration " << f[S::n_q + 1] << " on the ground, " << f_off[S::n_q + 1] << " off it");
    CHECK(f[S::n_q + 1] - f_off[S::n_q + 1] > 2);
    agree_at(ball, x, 0.0, k, false);
  }
}
