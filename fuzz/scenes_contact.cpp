// The scenes fuzz target's contact scenes (fuzz/scenes_fuzz.hpp): the shapes
// of models/shapes.hpp (a capsule and a box on the ground, a ball on the
// box) with their sizes, materials and the ground's friction from the
// bytes; and the quadruped (scenes_legged.cpp).
#include <flange/models/shapes.hpp>

#include "scenes_fuzz.hpp"

namespace flange::fuzz {

void fuzz_contacts(bytes& b, int which) {
  if (which == 0) {
    run(b, true, [&] {
      models::shapes_params p;
      p.rod_mass = b.num(0.2, 3);
      p.crate_mass = b.num(0.2, 3);
      p.ball_mass = b.num(0.2, 3);
      p.rod_inertia = b.inertia();
      p.crate_inertia = b.inertia();
      p.ball_inertia = b.inertia();
      p.rod = {.radius = b.num(0.05, 0.5), .half_length = b.num(0, 0.8), .center = b.vec(-0.1, 0.1),
               .axis = b.direction()};
      const Vec3d h(b.num(0.1, 0.7), b.num(0.1, 0.7), b.num(0.1, 0.7));
      p.crate = {.half_extents = h, .center = b.vec(-0.1, 0.1), .corner_radius = b.num(0.005, 0.05)};
      p.ball_radius = b.num(0.05, 0.8);
      p.material = material(b);
      p.transition_velocity = b.num(1e-3, 0.1);
      return models::shapes_on_ground(p);
    });
  } else {
    fuzz_legged_contact(b);  // its own unit (scenes_legged.cpp): the two compile side by side
  }
}

}  // namespace flange::fuzz
