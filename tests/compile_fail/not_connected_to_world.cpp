// Two bodies joined to each other but to nothing else: every frame is
// connected, yet no path reaches the World.
#include <flange/equations_of_motion.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}),
#ifdef FLANGE_KO
               Body<"spare">({.m = 1.0}), Body<"other">({.m = 1.0}), connect<"spare.frame_a", "other.frame_a">,
#endif
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "mass.frame_a">);
int main() {}
