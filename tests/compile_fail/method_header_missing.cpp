// A method that flange declares, used without its header: one error naming
// the header to include.
#include <flange/flange.hpp>
#ifndef FLANGE_KO
#include <flange/simulate/bulirsch_stoer.hpp>
#endif
using namespace flange;
int main() {
  const auto arm = scene(World<"world">{}, Revolute<"shoulder", axis::z>{}, Body<"mass">({.m = 1}),
                         connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "mass.frame_a">);
  const auto x = simulate<method::bulirsch_stoer>(arm, decltype(arm)::state_type{0.1, 0.0}, 0.0, 0.1, {});
  return x[0] > 0;
}
