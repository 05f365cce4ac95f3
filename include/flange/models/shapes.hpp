// Shapes on the ground: three free bodies with every kind of contact shape,
// for the contact law tests and the fuzz target. A rod with a capsule and a
// crate with a box, each against the ground (the half-space y ≤ 0), and a
// ball that touches the crate's box: Contacts "rod_ground" (capsule–half
// space), "crate_ground" (box–half space) and "ball_crate" (sphere–box).
// Gravity along −y.
#pragma once
#include "flange/components/body.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/contact.hpp"
#include "flange/joints/free_motion.hpp"
#include "flange/scene/scene.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

struct shapes_params {
  double rod_mass = 1.5, crate_mass = 2.0, ball_mass = 0.5;
  Mat3d rod_inertia = Vec3d(0.02, 0.03, 0.01).asDiagonal();
  Mat3d crate_inertia = Vec3d(0.02, 0.04, 0.03).asDiagonal();
  Mat3d ball_inertia = Mat3d::Identity() * 0.002;
  contact_shape::capsule rod{.radius = 0.5, .half_length = 0.8, .axis = Vec3d(1, 1, 0).normalized()};
  contact_shape::box crate{.half_extents = {0.6, 0.5, 0.7}, .center = {0.1, 0, 0}, .corner_radius = 0.05};
  double ball_radius = 0.8;
  contact_material material{.stiffness = 1e6, .dissipation = 0.3, .static_friction = 0.7, .dynamic_friction = 0.5,
                            .viscous_friction = 0.1};
  double transition_velocity = 0.1;
};

[[nodiscard]] inline auto shapes_on_ground(const shapes_params& p = {}) {
  const contact_material& m = p.material;
  const double vt = p.transition_velocity;
  return scene(
      World<"world">{}, FreeMotion<"fr">{}, Body<"rod">({.m = p.rod_mass, .J = p.rod_inertia}), FreeMotion<"fb">{},
      Body<"crate">({.m = p.crate_mass, .J = p.crate_inertia}), FreeMotion<"fs">{},
      Body<"ball">({.m = p.ball_mass, .J = p.ball_inertia}),
      Contact<"rod_ground", contact_shape::capsule, contact_shape::half_space>(
          {.a = p.rod, .b = {.n = {0, 1, 0}}, .material_a = m, .material_b = m, .transition_velocity = vt}),
      Contact<"crate_ground", contact_shape::box, contact_shape::half_space>(
          {.a = p.crate, .b = {.n = {0, 1, 0}}, .material_a = m, .material_b = m, .transition_velocity = vt}),
      Contact<"ball_crate", contact_shape::sphere, contact_shape::box>(
          {.a = {.radius = p.ball_radius}, .b = p.crate, .material_a = m, .material_b = m, .transition_velocity = vt}),
      connect<"world.frame_b", "fr.frame_a">, connect<"fr.frame_b", "rod.frame_a">,
      connect<"world.frame_b", "fb.frame_a">, connect<"fb.frame_b", "crate.frame_a">,
      connect<"world.frame_b", "fs.frame_a">, connect<"fs.frame_b", "ball.frame_a">,
      connect<"fr.frame_b", "rod_ground.frame_a">, connect<"world.frame_b", "rod_ground.frame_b">,
      connect<"fb.frame_b", "crate_ground.frame_a">, connect<"world.frame_b", "crate_ground.frame_b">,
      connect<"fs.frame_b", "ball_crate.frame_a">, connect<"fb.frame_b", "ball_crate.frame_b">);
}

}  // namespace flange::models
