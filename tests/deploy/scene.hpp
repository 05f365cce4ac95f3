// A pendulum, built into a Python module by the consumer project through the
// installed flange_add_python_module.
#pragma once
#include <flange/flange.hpp>
namespace deployed {
inline auto make_scene() {
  using namespace flange;
  return scene(World<"world">{}, Revolute<"pivot", axis::z>{}, FixedTranslation<"rod">({.d = {1, 0, 0}}),
               PointMass<"bob">({.m = 1}), connect<"world.frame_b", "pivot.frame_a">,
               connect<"pivot.frame_b", "rod.frame_a">, connect<"rod.frame_b", "bob.frame_a">);
}
}  // namespace deployed
