// Compile-time probe: the smallest scene a user writes, simulated with the
// default method and printed (the edit-compile loop of docs/performance.md).
#include <cstdio>

#include <flange/flange.hpp>
using namespace flange;

int main() {
  const auto pendulum = scene(World<"world">({.g = {0, -9.81, 0}}), Revolute<"joint", axis::z>{},
                              FixedTranslation<"rod">({.d = {1.0, 0, 0}}), Body<"bob">({.m = 1.0}),
                              connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                              connect<"rod.frame_b", "bob.frame_a">);
  const auto x = simulate(pendulum, initial_state<"joint">(pendulum, {.q = 0.5}), 0.0, 10.0);
  std::printf("%.12f %.12f\n", x[0], x[1]);
}
