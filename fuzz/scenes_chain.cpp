// The scenes fuzz target's spatial chain on run-time axes and the paper's
// gantry crane (fuzz/scenes_fuzz.hpp).
#include "scenes_fuzz.hpp"

namespace flange::fuzz {

void fuzz_chain_and_crane(bytes& b, int which) {
  if (which == 0) {
    run(b, true, [&] {
      models::chain_params<4> p;
      for (int i = 0; i < 4; ++i) {
        p.axis[i] = b.direction();
        p.d[i] = Vec3d(b.num(0.2, 1), b.num(-0.3, 0.3), b.num(-0.3, 0.3));
        p.m[i] = b.num(0.2, 2);
        p.J[i] = b.inertia();
      }
      p.g = b.vec(-10, 10);
      return models::chain<4, models::runtime_axes>(p);
    });
  } else {
    run(b, true, [&] {
      return models::gantry_crane({.M = b.num(0.1, 10), .m = b.num(0.1, 10), .d = b.num(0.1, 3), .g = b.num(1, 20)},
                                  b.num(-5, 5));
    });
  }
}

}  // namespace flange::fuzz
