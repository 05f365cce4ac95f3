// A ball on the ground: a free body with a sphere that touches the
// half-space y ≤ 0 (a Contact "ball_ground"), gravity along −y. The
// contact's stiffness may be given as the linear stiffness it has at rest
// under the ball's weight (rest_stiffness, N/m): the slope of the
// Hunt–Crossley force there, (3/2)·m·g/δ_rest, is what a stepper's stability
// sees. Used by the contact benchmarks and tests.
#pragma once
#include <cmath>

#include "flange/components/body.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/contact.hpp"
#include "flange/joints/free_motion.hpp"
#include "flange/scene/scene.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

struct ball_params {
  double m = 1.0, radius = 0.1;
  contact_material material{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.8, .dynamic_friction = 0.6};
  double transition_velocity = 1e-3;
};

/// The penetration at which the ball rests (the same material on both
/// sides, so k = E^(2/3)/2): m·g = (4/3)·k·δ·√(R·k·δ).
[[nodiscard]] inline double rest_depth(const ball_params& p, double g = 9.81) {
  const double k = std::cbrt(p.material.stiffness * p.material.stiffness) / 2;
  return std::pow(3 * p.m * g / (4 * k * std::sqrt(p.radius * k)), 2.0 / 3.0);
}

/// The material stiffness E [Pa] that gives the ball a linear stiffness
/// k_lin [N/m] at rest: δ_rest = (3/2)·m·g/k_lin, then E from Hertz's law.
[[nodiscard]] inline double stiffness_for(const ball_params& p, double k_lin, double g = 9.81) {
  const double depth = 1.5 * p.m * g / k_lin;
  const double k = std::pow(3 * p.m * g / (4 * std::pow(depth, 1.5) * std::sqrt(p.radius)), 2.0 / 3.0);
  return std::pow(2 * k, 1.5);
}

/// The ball (a solid sphere: J = (2/5)·m·r²) above the ground.
[[nodiscard]] inline auto ball_on_ground(const ball_params& p = {}) {
  return scene(World<"world">{}, FreeMotion<"fly">{},
               Body<"ball">({.m = p.m, .J = Mat3d::Identity() * (0.4 * p.m * p.radius * p.radius)}),
               Contact<"ball_ground", contact_shape::sphere, contact_shape::half_space>(
                   {.a = {.radius = p.radius}, .b = {.n = {0, 1, 0}}, .material_a = p.material,
                    .material_b = p.material, .transition_velocity = p.transition_velocity}),
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "ball.frame_a">,
               connect<"fly.frame_b", "ball_ground.frame_a">, connect<"world.frame_b", "ball_ground.frame_b">);
}

}  // namespace flange::models
