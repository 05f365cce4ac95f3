#include <flange/equations_of_motion.hpp>
using namespace flange;
#ifdef FLANGE_KO
constexpr auto c = connect<"joint.frame_c", "mass.frame_a">;
#else
constexpr auto c = connect<"joint.frame_b", "mass.frame_a">;
#endif
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}),
               connect<"world.frame_b", "joint.frame_a">, c);
int main() {}
