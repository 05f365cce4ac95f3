// The scenes fuzz target's quadruped (fuzz/scenes_fuzz.hpp): models/legged.hpp
// on sphere feet and a box belly under PD drives of fuzzed gains, its masses,
// feet and materials from the bytes.
#include <flange/models/legged.hpp>

#include "scenes_fuzz.hpp"

namespace flange::fuzz {

void fuzz_legged_contact(bytes& b) {
  run(b, true, [&] {
    models::legged_params p;
    p.trunk_mass = b.num(2, 20);
    p.link_mass = b.num(0.1, 1);
    p.foot_radius = b.num(0.01, 0.05);
    p.foot = material(b);
    p.ground = material(b);
    p.transition_velocity = b.num(1e-3, 0.1);
    return models::legged<4, 3, true, true>(
        p, models::crouch_drive{.kp = b.num(0, 2000), .kd = b.num(0, 100), .knee = b.num(-0.5, 0.5)});
  });
}

}  // namespace flange::fuzz
