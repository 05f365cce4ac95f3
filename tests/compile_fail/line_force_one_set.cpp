// A spring whose two ends are in one connection set has no line to act along.
// The ok half hangs it between the World and the arm's end.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, FixedTranslation<"rod">({.d = {1, 0, 0}}),
               Body<"mass">({.m = 1.0}), Spring<"spring">({.c = 10.0, .s0 = 0.5}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">, connect<"world.frame_b", "spring.frame_a">,
#ifdef FLANGE_KO
               connect<"world.frame_b", "spring.frame_b">
#else
               connect<"rod.frame_b", "spring.frame_b">
#endif
);
int main() {
  std::array<double, 2> x{1.0, 0.0}, dx{};
  s(x, dx, 0.0);
}
