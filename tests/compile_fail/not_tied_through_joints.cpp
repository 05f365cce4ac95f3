// A body held only by a Torque element floats: it has no joint coordinates.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}),
               Torque<"motor">({.M_ext = Vec3d::Zero()}), Body<"free">({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "mass.frame_a">,
               connect<"world.frame_b", "motor.frame_a">,
#ifdef FLANGE_KO
               connect<"motor.frame_b", "free.frame_a">
#else
               connect<"motor.frame_b", "free.frame_a">, connect<"free.frame_a", "mass.frame_a">
#endif
);
int main() {
  std::array<double, 2> x{}, dx{};
  s(x, dx, 0.0);
}
