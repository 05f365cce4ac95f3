// A WorldForce connected to the World's own frame pushes on nothing that
// moves. The ok half pushes the arm's end.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, FixedTranslation<"rod">({.d = {1, 0, 0}}),
               Body<"mass">({.m = 1.0}), WorldForce<"push">({.value = Vec3d(1, 0, 0)}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">,
#ifdef FLANGE_KO
               connect<"world.frame_b", "push.frame_b">
#else
               connect<"rod.frame_b", "push.frame_b">
#endif
);
int main() {
  std::array<double, 2> x{1.0, 0.0}, dx{};
  s(x, dx, 0.0);
}
