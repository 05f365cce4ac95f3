// A free body carrying a ball-jointed pendulum, for the Python tests of 3-D
// joints: initial_state's orientation forms and a FreeMotion's v_cm
// (tests/python/test_api.py), and momentum conservation through Python.
#pragma once
#include <flange/flange.hpp>

namespace free_body {
inline auto make_scene() {
  using namespace flange;
  return scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"base">{},
               Body<"hull", cm::offset>({.m = 3.0, .J = Vec3d(0.2, 0.3, 0.4).asDiagonal().toDenseMatrix(), .r_cm = {0.1, 0, 0}}),
               Spherical<"ball">{}, FixedTranslation<"arm">({.d = {0.5, 0, 0}}),
               Body<"bob">({.m = 1.0, .J = Mat3d::Identity() * 0.01}),
               connect<"world.frame_b", "base.frame_a">, connect<"base.frame_b", "hull.frame_a">,
               connect<"base.frame_b", "ball.frame_a">, connect<"ball.frame_b", "arm.frame_a">,
               connect<"arm.frame_b", "bob.frame_a">);
}
}  // namespace free_body
