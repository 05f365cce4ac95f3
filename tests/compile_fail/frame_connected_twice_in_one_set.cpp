// The robot arm with one connection too many: motor.frame_b and rod.frame_a
// are already in one set through joint.frame_b.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Torque<"motor">({.M_ext = Vec3d::Zero()}), Revolute<"joint", axis::z>{},
               FixedTranslation<"rod">({.d = {1, 0, 0}}), Body<"mass">({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, connect<"world.frame_b", "motor.frame_a">,
               connect<"joint.frame_b", "rod.frame_a">, connect<"joint.frame_b", "motor.frame_b">,
#ifdef FLANGE_KO
               connect<"motor.frame_b", "rod.frame_a">,
#endif
               connect<"rod.frame_b", "mass.frame_a">);
int main() {}
