#include <flange/equations_of_motion.hpp>
using namespace flange;
#ifdef FLANGE_KO
auto s = scene(FixedTranslation<"rod">({.d = {1, 0, 0}}), Body<"mass">({.m = 1.0}),
               connect<"rod.frame_b", "mass.frame_a">);
#else
auto s = scene(World<"world">{}, FixedTranslation<"rod">({.d = {1, 0, 0}}), Body<"mass">({.m = 1.0}),
               connect<"world.frame_b", "rod.frame_a">, connect<"rod.frame_b", "mass.frame_a">);
#endif
int main() {}
