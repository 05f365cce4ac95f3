#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{},
#ifdef FLANGE_KO
               World<"ground">{},
#endif
               Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}), connect<"world.frame_b", "joint.frame_a">,
               connect<"joint.frame_b", "mass.frame_a">);
int main() {}
