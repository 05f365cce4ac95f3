// The laws of tree_laws.hpp on scenes with contacts, at random states (some
// deep in the ground, some apart, slipping every way): the derivative equals
// a second algorithm (the articulated body, and its shared steps), the
// residual vanishes on the recovered variables, and the power balance holds
// with the contacts' power from their recovered flows. The quadruped with
// its sphere feet and box belly, and models::shapes_on_ground (a capsule,
// a box and a ball on the box).
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/legged.hpp>
#include <flange/models/shapes.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
template <class S>
test::law_errors laws(const S& s, unsigned seed) {
  std::mt19937 rng(seed);
  test::law_errors e;
  test::check_laws(s, rng, e, 20);
  return e;
}

/// Of 20 random states drawn as check_laws draws them, how many have the
/// contact `Name` touching (so that the laws above were not checked apart only).
template <fixed_string Name, fixed_string Depth, class S>
int touching(const S& s, unsigned seed) {
  std::mt19937 rng(seed);
  int n = 0;
  for (int k = 0; k < 20; ++k) {
    const auto x = test::random_state(s, rng);
    const double t = test::uniform(rng, 0, 1);
    n += recover(s, t, x).template internal<Name, Depth>() > 0;
  }
  return n;
}

/// The laws hold to round-off (as for the random trees, tree_test.cpp:
/// amplified by the mass matrix's conditioning).
void laws_hold(const test::law_errors& e) {
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);
}
}  // namespace

TEST_CASE("laws with contacts: a quadruped on sphere feet and a box belly, under PD drives") {
  const auto s = models::legged<4, 3, true, true>({.transition_velocity = 0.03}, models::crouch_drive{});
  const auto e = laws(s, 7);
  const int feet = touching<"foot0", "δ">(s, 7), belly = touching<"belly", "δ[0]">(s, 7);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power balance " << e.power << "; foot0 down in "
                   << feet << ", belly corner 0 in " << belly << " of 20 states");
  CHECK(feet > 0);
  CHECK(belly > 0);
  laws_hold(e);
}

TEST_CASE("laws with contacts: a capsule on the ground and a ball on a free box") {
  const auto s = models::shapes_on_ground();
  const auto e = laws(s, 11);
  const int rod = touching<"rod_ground", "δ[0]">(s, 11), crate = touching<"crate_ground", "δ[0]">(s, 11),
            ball = touching<"ball_crate", "δ">(s, 11);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power balance " << e.power << "; touching in "
                   << rod << ", " << crate << ", " << ball << " of 20 states");
  CHECK(rod > 0);
  CHECK(crate > 0);
  CHECK(ball > 0);
  laws_hold(e);
}

TEST_CASE("laws with contacts: shapes at turned frames against a turned, moved ground") {
  // The derivative meets a half-space at rest in the World in its shape's
  // link coordinates; the residual meets it in world coordinates
  // (contact.hpp): their agreement is the check, with both the shapes'
  // frames and the ground's turned and moved off their links.
  const contact_material m{.stiffness = 1e6, .dissipation = 0.3, .static_friction = 0.7, .dynamic_friction = 0.5,
                           .viscous_friction = 0.1};
  const auto s = scene(
      World<"world">{}, FixedRotation<"slope">({.r = {0.2, -0.3, 0.1}, .R = orientation::rpy(0.2, -0.1, 0.4)}),
      FreeMotion<"fr">{}, Body<"rod">({.m = 1.5, .J = Vec3d(0.02, 0.03, 0.01).asDiagonal()}),
      FixedRotation<"grip">({.r = {0.1, 0.2, -0.05}, .R = orientation::axis_angle({1, 1, 0}, 0.7)}),
      Revolute<"hinge", axis::z>{}, Body<"paddle">({.m = 0.8, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
      FixedRotation<"mount">({.r = {0.3, 0, 0}, .R = orientation::rpy(-0.3, 0.5, 0.2)}),
      Contact<"rod_ground", contact_shape::capsule, contact_shape::half_space>(
          {.a = {.radius = 0.5, .half_length = 0.8, .axis = Vec3d(1, 1, 0).normalized()},
           .b = {.n = Vec3d(0.1, 1, 0.2).normalized(), .offset = 0.05}, .material_a = m, .material_b = m,
           .transition_velocity = 0.1}),
      Contact<"paddle_ground", contact_shape::box, contact_shape::half_space>(
          {.a = {.half_extents = {0.6, 0.5, 0.7}, .center = {0.1, 0, 0}, .corner_radius = 0.05},
           .b = {.n = {0, 1, 0}, .offset = -0.1}, .material_a = m, .material_b = m, .transition_velocity = 0.1}),
      connect<"world.frame_b", "slope.frame_a">, connect<"world.frame_b", "fr.frame_a">,
      connect<"fr.frame_b", "rod.frame_a">, connect<"fr.frame_b", "grip.frame_a">,
      connect<"grip.frame_b", "rod_ground.frame_a">, connect<"slope.frame_b", "rod_ground.frame_b">,
      connect<"fr.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "paddle.frame_a">,
      connect<"hinge.frame_b", "mount.frame_a">, connect<"mount.frame_b", "paddle_ground.frame_a">,
      connect<"slope.frame_b", "paddle_ground.frame_b">);
  const auto e = laws(s, 5);
  const int rod = touching<"rod_ground", "δ[0]">(s, 5), paddle = touching<"paddle_ground", "δ[0]">(s, 5);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power balance " << e.power << "; touching in "
                   << rod << ", " << paddle << " of 20 states");
  CHECK(rod > 0);
  CHECK(paddle > 0);
  laws_hold(e);
}
