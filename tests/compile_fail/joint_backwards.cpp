// A FreeMotion (or a Planar joint) must be connected frame_a toward the
// World; connected the other way round it is refused in one line.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"b">({.m = 1.0, .J = Mat3d::Identity()}),
#ifdef FLANGE_KO
               connect<"world.frame_b", "fly.frame_b">, connect<"fly.frame_a", "b.frame_a">
#else
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">
#endif
);
int main() {
  auto x = neutral_state(s), dx = x;
  s(x, dx, 0.0);
}
