#include <flange/equations_of_motion.hpp>
using namespace flange;
#ifdef FLANGE_KO
constexpr auto bad = connect<"joint.frame_a", "joint.frame_a">;
#else
constexpr auto bad = connect<"joint.frame_b", "mass.frame_a">;
#endif
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, bad);
int main() {}
