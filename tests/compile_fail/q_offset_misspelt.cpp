// Where a joint's coordinates start in the state, by name: a misspelt name
// is one error with "did you mean", as for every other name.
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
  const auto arm = scene(World<"world">{}, Revolute<"shoulder", axis::z>{}, Body<"mass">({.m = 1}),
                         connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "mass.frame_a">);
  using S = decltype(arm);
#ifdef FLANGE_KO
  constexpr int at = S::q_offset<"sholder">();
#else
  constexpr int at = S::q_offset<"shoulder">();
#endif
  return at;
}
