// A cut Spherical turns by a quaternion, not by coordinates whose distance
// from a target Newton's method can close: initial_state and close_loops
// refuse to hold it, in one error naming it. (The same loop cut at a
// Revolute holds that one.)
#include <flange/equations_of_motion.hpp>
using namespace flange;
using models::bar;
int main() {
  auto s = scene(World<"world">{}, Revolute<"r1", axis::z>{}, bar<"crank">(0.4, 1.0), Revolute<"r2", axis::y>{},
                 bar<"rod">(0.8, 1.0), FixedTranslation<"ground">({.d = {1.2, 0, 0}}), Revolute<"r3", axis::y>{},
                 bar<"rocker">(0.4, 1.0), Spherical<"s">{},
                 connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "crank.frame_a">,
                 connect<"crank.frame_b", "r2.frame_a">, connect<"r2.frame_b", "rod.frame_a">,
                 connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "r3.frame_a">,
                 connect<"r3.frame_b", "rocker.frame_a">, connect<"rod.frame_b", "s.frame_a">,
                 connect<"rocker.frame_b", "s.frame_b">);
  auto x = neutral_state(s);
#ifdef FLANGE_KO
  close_loops<"s">(s, x);
#else
  close_loops<"r1">(s, x);
#endif
  return x[0] == 0 ? 0 : 1;
}
