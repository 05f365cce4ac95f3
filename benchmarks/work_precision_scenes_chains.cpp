// The work-precision study's scenes: the paper's arm and crane, a double
// pendulum, a spatial chain and a stiff joint.
#include <array>
#include <cmath>

#include <flange/models/chain.hpp>
#include <flange/models/paper.hpp>

#include "work_precision_study.hpp"

namespace work_precision {

void study_chains(const options& o, std::vector<study::point>& points, std::ostream& refs) {
  // The paper's arm, swinging freely from 57° above horizontal (θ0 = 2.6 rad).
  study_scene("robot_arm", models::robot_arm(), {1.0, 0.0}, 5.0, true, o, points, refs);
  // The paper's crane, the load released at θ = 1 rad with the cart moving.
  study_scene("gantry_crane", models::gantry_crane(), {0.0, 1.0 - M_PI / 2, 0.5, 0.0}, 5.0, false, o, points, refs);
  {
    // A double pendulum released from near upright: chaotic.
    models::chain_params<2> p;
    for (int i = 0; i < 2; ++i) {
      p.d[i] = Vec3d(1, 0, 0);
      p.m[i] = 1;
      p.J[i] = Mat3d::Identity() * 0.01;
    }
    study_scene("double_pendulum", models::chain<2, models::planar_axes>(p), {2.5, 0.5, 0.0, 0.0}, 5.0, false, o,
                points, refs);
  }
  {
    // Four links, non-parallel run-time axes, offsets out of the plane.
    models::chain_params<4> p;
    p.axis = {Vec3d(0, 0, 1), Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(1, 1, 1).normalized()};
    for (int i = 0; i < 4; ++i) {
      p.d[i] = Vec3d(0.4, 0.1 * (i % 2), -0.05 * i);
      p.m[i] = 1.0 - 0.15 * i;
      p.J[i] = Vec3d(0.01, 0.02, 0.015).asDiagonal();
    }
    study_scene("spatial_chain4", models::chain<4, models::runtime_axes>(p), {0.3, -0.4, 0.5, 0.2, 0, 0, 0, 0},
                3.0, false, o, points, refs);
  }
  {
    // A pendulum with a stiff, critically damped elbow spring (ω ≈ 2900 rad/s
    // against the swing's ≈ 3 rad/s): the fast mode dies in a millisecond, then
    // only stability holds explicit steppers back.
    const double c = 1e6, I2 = 0.005 + 0.5 * 0.25;
    const auto stiff = scene(
        World<"world">({.g = {0, -9.81, 0}}), Revolute<"shoulder", axis::z>{},
        FixedTranslation<"upper">({.d = {1, 0, 0}}), Body<"b1">({.m = 1.0, .J = Mat3d::Identity() * 0.01}),
        Revolute<"elbow", axis::z, axis_law::spring_damper>({.c = c, .d = 2 * std::sqrt(c * I2), .phi0 = 0.0}),
        FixedTranslation<"lower">({.d = {0.5, 0, 0}}), Body<"b2">({.m = 0.5, .J = Mat3d::Identity() * 0.005}),
        connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
        connect<"upper.frame_b", "b1.frame_a">, connect<"upper.frame_b", "elbow.frame_a">,
        connect<"elbow.frame_b", "lower.frame_a">, connect<"lower.frame_b", "b2.frame_a">);
    study_scene("stiff_joint", stiff, {0.5, 0.3, 0.0, 0.0}, 2.0, false, o, points, refs);
  }
}

}  // namespace work_precision
