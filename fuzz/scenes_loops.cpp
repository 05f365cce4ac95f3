// The scenes fuzz target's closed loops (fuzz/scenes_fuzz.hpp): a four-bar
// cut at a revolute joint and a slider-crank with a prismatic joint in its loop.
#include "scenes_fuzz.hpp"

namespace flange::fuzz {

void fuzz_loops(bytes& b, int which) {
  if (which == 0) {
    run(b, false, [&] {
      models::fourbar_params p;
      p.crank = b.num(0.2, 0.4);
      p.coupler = b.num(0.9, 1.1);
      p.rocker = b.num(0.7, 0.9);
      p.m_crank = b.num(0.5, 2);
      p.m_coupler = b.num(0.5, 2);
      p.m_rocker = b.num(0.5, 2);
      return models::fourbar(p);
    });
  } else {
    run(b, false, [&] {
      models::slider_crank_params p;
      p.crank = b.num(0.05, 0.15);
      p.rod = b.num(0.3, 0.5);
      p.m_crank = b.num(0.5, 2);
      p.m_rod = b.num(0.2, 1);
      p.m_piston = b.num(0.5, 2);
      return models::slider_crank(p);
    });
  }
}

}  // namespace flange::fuzz
