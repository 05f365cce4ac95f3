// Two FixedTranslations from the World's frame back to it close a loop of
// rigid components only: no joint in it can be cut, and nothing can move.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, FixedTranslation<"rod">({.d = {1, 0, 0}}),
               Body<"mass">({.m = 1.0}), FixedTranslation<"out">({.d = {1, 0, 0}}),
               FixedTranslation<"back">({.d = {-1, 0, 0}}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">, connect<"world.frame_b", "out.frame_a">,
               connect<"out.frame_b", "back.frame_a">
#ifdef FLANGE_KO
               , connect<"back.frame_b", "world.frame_b">
#endif
);
int main() {
  std::array<double, 2> x{}, dx{};
  s(x, dx, 0.0);
}
