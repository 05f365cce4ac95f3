#include <flange/equations_of_motion.hpp>
using namespace flange;
#ifdef FLANGE_KO
using Second = Body<"mass">;
#else
using Second = Body<"mass2">;
#endif
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}), Second({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "mass.frame_a">,
               connect<"joint.frame_b", Second::name + ".frame_a">);
int main() {}
