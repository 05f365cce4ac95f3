// The laws of tree_laws.hpp on scenes with contacts, at random states (some
// deep in the ground, some apart, slipping every way): the derivative equals
// a second algorithm (the articulated body, and its shared steps), the
// residual vanishes on the recovered variables, and the power balance holds
// with the contacts' power from their recovered flows. The quadruped with
// its sphere feet and box belly, and a capsule and a ball on a free box.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/legged.hpp>

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
}  // namespace

TEST_CASE("laws with contacts: a quadruped on sphere feet and a box belly, under PD drives") {
  const auto s = models::legged<4, 3, true, true>({.transition_velocity = 0.03}, models::crouch_drive{});
  const auto e = laws(s, 7);
  const int feet = touching<"foot0", "δ">(s, 7), belly = touching<"belly", "δ[0]">(s, 7);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power balance " << e.power << "; foot0 down in "
                   << feet << ", belly corner 0 in " << belly << " of 20 states");
  CHECK(feet > 0);
  CHECK(belly > 0);
  // As for the random trees (tree_test.cpp): round-off, amplified by the
  // mass matrix's conditioning.
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);
}

TEST_CASE("laws with contacts: a capsule on the ground and a ball on a free box") {
  const contact_material m{.stiffness = 1e6, .dissipation = 0.3, .static_friction = 0.7, .dynamic_friction = 0.5,
                           .viscous_friction = 0.1};
  const auto s = scene(
      World<"world">{}, FreeMotion<"fr">{}, Body<"rod">({.m = 1.5, .J = Vec3d(0.02, 0.03, 0.01).asDiagonal()}),
      FreeMotion<"fb">{}, Body<"crate">({.m = 2.0, .J = Vec3d(0.02, 0.04, 0.03).asDiagonal()}), FreeMotion<"fs">{},
      Body<"ball">({.m = 0.5, .J = Mat3d::Identity() * 0.002}),
      Contact<"rod_ground", contact_shape::capsule, contact_shape::half_space>(
          {.a = {.radius = 0.5, .half_length = 0.8, .axis = Vec3d(1, 1, 0).normalized()}, .b = {.n = {0, 1, 0}},
           .material_a = m, .material_b = m, .transition_velocity = 0.1}),
      Contact<"crate_ground", contact_shape::box, contact_shape::half_space>(
          {.a = {.half_extents = {0.6, 0.5, 0.7}, .center = {0.1, 0, 0}, .corner_radius = 0.05}, .b = {.n = {0, 1, 0}},
           .material_a = m, .material_b = m, .transition_velocity = 0.1}),
      Contact<"ball_crate", contact_shape::sphere, contact_shape::box>(
          {.a = {.radius = 0.8}, .b = {.half_extents = {0.6, 0.5, 0.7}, .center = {0.1, 0, 0}, .corner_radius = 0.05},
           .material_a = m, .material_b = m, .transition_velocity = 0.1}),
      connect<"world.frame_b", "fr.frame_a">, connect<"fr.frame_b", "rod.frame_a">,
      connect<"world.frame_b", "fb.frame_a">, connect<"fb.frame_b", "crate.frame_a">,
      connect<"world.frame_b", "fs.frame_a">, connect<"fs.frame_b", "ball.frame_a">,
      connect<"fr.frame_b", "rod_ground.frame_a">, connect<"world.frame_b", "rod_ground.frame_b">,
      connect<"fb.frame_b", "crate_ground.frame_a">, connect<"world.frame_b", "crate_ground.frame_b">,
      connect<"fs.frame_b", "ball_crate.frame_a">, connect<"fb.frame_b", "ball_crate.frame_b">);
  const auto e = laws(s, 11);
  const int rod = touching<"rod_ground", "δ[0]">(s, 11), crate = touching<"crate_ground", "δ[0]">(s, 11),
            ball = touching<"ball_crate", "δ">(s, 11);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power balance " << e.power << "; touching in "
                   << rod << ", " << crate << ", " << ball << " of 20 states");
  CHECK(rod > 0);
  CHECK(crate > 0);
  CHECK(ball > 0);
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);
}
