// Simbody's Force::MobilityLinearStop on two scenes that stops_test.cpp
// builds in flange with the same numbers (stops_scenes.hpp): a pendulum on a
// Pin that falls onto its lower stop, and a block on a Slider that bounces
// between its stops. Writes to the file named by its argument, for each
// scene, "scene t q u" every 0.01 s over 3 s, integrated with
// Runge–Kutta–Merson at accuracy 1e-12.
//
// Its own C++17 program with no flange header (Simbody 3.7's headers do not
// compile as C++20; Debian's library is built without NDEBUG, so this file
// is too: see benchmarks/peers/simbody_peer.cpp).
#include <Simbody.h>

#include <cstdio>

#include "stops_scenes.hpp"

using namespace SimTK;

namespace {
void run(std::FILE* out, const char* name, bool pendulum) {
  namespace s = stops_scenes;
  MultibodySystem system;
  SimbodyMatterSubsystem matter(system);
  GeneralForceSubsystem forces(system);
  Force::UniformGravity gravity(forces, matter, Vec3(0, -s::g, 0));
  MobilizedBody joint;
  if (pendulum) {
    const Vec3 c(s::L, 0, 0);
    const Body::Rigid bob(MassProperties(s::m, c, Inertia(Vec3(s::J[0], s::J[1], s::J[2])).shiftFromMassCenter(-c, s::m)));
    joint = MobilizedBody::Pin(matter.Ground(), Transform(), bob, Transform());
    Force::MobilityLinearStop(forces, joint, MobilizerQIndex(0), s::pin_k, s::pin_d, s::pin_lower, s::pin_upper);
  } else {
    const Body::Rigid block(MassProperties(s::m, Vec3(0), Inertia(Vec3(s::J[0], s::J[1], s::J[2]))));
    joint = MobilizedBody::Slider(matter.Ground(), Transform(), block, Transform());
    Force::MobilityLinearStop(forces, joint, MobilizerQIndex(0), s::slider_k, s::slider_d, s::slider_lower,
                              s::slider_upper);
  }
  system.realizeTopology();
  State state = system.getDefaultState();
  joint.setOneQ(state, 0, pendulum ? s::pin_q0 : s::slider_q0);
  joint.setOneU(state, 0, pendulum ? s::pin_u0 : s::slider_u0);
  RungeKuttaMersonIntegrator integ(system);
  integ.setAccuracy(1e-12);
  TimeStepper ts(system, integ);
  ts.initialize(state);
  for (int k = 0; k <= s::samples; ++k) {
    const double t = k * s::dt;
    if (k > 0) ts.stepTo(t);
    const State& now = integ.getState();
    std::fprintf(out, "%s %.17g %.17g %.17g\n", name, t, joint.getOneQ(now, 0), joint.getOneU(now, 0));
  }
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: simbody_stops <output file>\n");
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  run(out, "pendulum", true);
  run(out, "slider", false);
  return std::fclose(out) == 0 ? 0 : 1;
}
