// A Contact between two shapes whose pair is not supported (two boxes):
// one error listing the pairs there are.
#include <flange/flange.hpp>
using namespace flange;
#ifdef FLANGE_KO
using Shape = contact_shape::box;
#else
using Shape = contact_shape::sphere;
#endif
int main() {
  const contact_material steel{};
  const auto s = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"crate">({.m = 1}),
                       Contact<"crates", Shape, contact_shape::box>(
                           {.b = {.half_extents = {1, 1, 1}}, .material_a = steel, .material_b = steel}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "crate.frame_a">,
                       connect<"fly.frame_b", "crates.frame_a">, connect<"world.frame_b", "crates.frame_b">);
  return decltype(s)::n_q == 7 ? 0 : 1;
}
