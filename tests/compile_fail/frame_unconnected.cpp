// A line force whose frame_b was never connected: the diagnostic names the
// frame and says to connect it (not to add joints).
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
  const auto s = scene(World<"world">({.g = {0, -9.81, 0}}), Revolute<"joint", axis::z>(),
                       FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1, .J = Mat3d::Identity()}),
                       SpringDamper<"sd">({.c = 1, .s0 = 0, .d = 1}),  //
                       connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                       connect<"rod.frame_b", "mass.frame_a">, connect<"sd.frame_a", "mass.frame_a">
#ifndef FLANGE_KO
                       , connect<"sd.frame_b", "world.frame_b">
#endif
  );
  std::array<double, 2> x{0.3, 0}, dx;
  s(x, dx, 0.0);
  return dx[1] < 0;
}
