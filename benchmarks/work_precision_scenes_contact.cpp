// The work-precision study's contact scenes: a bouncing ball, a sliding box
// and the standing quadruped.
#include <array>
#include <cmath>

#include <flange/models/ball.hpp>
#include <flange/models/legged.hpp>

#include "work_precision_study.hpp"

namespace work_precision {

void study_contact(const options& o, std::vector<study::point>& points, std::ostream& refs) {
  {
    // Contact: a ball thrown onto the ground (models/ball.hpp: Hunt–Crossley
    // at E = 1e7 Pa, about 3e6 N/m at rest, with Stribeck friction): it
    // lands twice, skidding, and rolls. The contact scenes' references are
    // dopri5's (study/work_precision.hpp: fehlberg78's error estimate can
    // step over a landing).
    const auto ball = models::ball_on_ground();
    study_scene("bouncing_ball", ball, {0, 0.3, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 0, 5.0}, 1.0, false, o, points,
                refs, study::reference_stepper::dopri5);
  }
  {
    // Contact: a box sliding on its face at 1 m/s, its eight corners'
    // spheres against the ground, until friction stops it.
    const contact_material m{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.5, .dynamic_friction = 0.5};
    const auto box = scene(
        World<"world">{}, FreeMotion<"fly">{}, Body<"box">({.m = 2.0, .J = Vec3d(0.02, 0.04, 0.03).asDiagonal()}),
        Contact<"box_ground", contact_shape::box, contact_shape::half_space>(
            {.a = {.half_extents = {0.2, 0.1, 0.15}, .corner_radius = 0.01}, .b = {.n = {0, 1, 0}},
             .material_a = m, .material_b = m, .transition_velocity = 1e-3}),
        connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "box.frame_a">,
        connect<"fly.frame_b", "box_ground.frame_a">, connect<"world.frame_b", "box_ground.frame_b">);
    study_scene("box_slide", box, {0, 0.0995, 0, 0, 0, 0, 1, 1.0, 0, 0, 0, 0, 0}, 0.5, false, o, points, refs,
                study::reference_stepper::dopri5);
  }
  {
    // Contact: the quadruped (models/legged.hpp) dropped onto its feet in a
    // crouch, standing under one PD law on its twelve joints.
    const auto robot = models::legged<4, 3, true, true>({.transition_velocity = 0.03}, models::crouch_drive{});
    study_scene("legged_stand", robot, models::crouched_state(robot), 1.0, false, o, points, refs,
                study::reference_stepper::dopri5);
  }
}

}  // namespace work_precision
