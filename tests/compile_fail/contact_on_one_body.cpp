// A Contact whose two shapes sit on one body (a sphere and a plane both
// fixed to the crate): one error saying they can never touch.
#include <flange/flange.hpp>
using namespace flange;
#ifdef FLANGE_KO
#define PLANE_ON "lid.frame_b"
#else
#define PLANE_ON "world.frame_b"
#endif
int main() {
  const contact_material steel{};
  const auto s = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"crate">({.m = 1}),
                       FixedTranslation<"lid">({.d = {0, 0.5, 0}}),
                       Contact<"rattle", contact_shape::sphere, contact_shape::half_space>(
                           {.a = {.radius = 0.1}, .material_a = steel, .material_b = steel}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "crate.frame_a">,
                       connect<"fly.frame_b", "lid.frame_a">, connect<"fly.frame_b", "rattle.frame_a">,
                       connect<PLANE_ON, "rattle.frame_b">);
  return decltype(s)::n_q == 7 ? 0 : 1;
}
