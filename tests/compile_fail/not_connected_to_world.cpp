#include <flange/flange.hpp>
using namespace flange;
auto s = scene(World<"world">{}, Revolute<"joint", axis::z>{}, Body<"mass">({.m = 1.0}),
#ifdef FLANGE_KO
               Body<"spare">({.m = 1.0}),
#endif
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "mass.frame_a">);
int main() {}
