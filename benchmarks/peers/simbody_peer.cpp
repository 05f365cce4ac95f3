// Simbody on the paper's robot arm and gantry crane and on a four-bar (a
// closed loop: a Ball constraint, projected by Simbody), measured the way
// benchmarks/work_precision.cpp measures flange: the scaled error at T against
// flange's long-double reference, and the median wall time per simulated
// second, over a sweep of accuracies for each of Simbody's integrators.
//
//   simbody_peer --reference FILE [--quick] [--scene NAME]
//
// The models match flange's (peer_common.hpp): a Pin (rotation about z) and a
// Slider (translation along x), the mass properties at the same places,
// uniform gravity along −y and no other force.
//
// Built as its own C++17 program with no flange header: Simbody 3.7's headers
// do not compile as C++20. Debian's libsimbody is built without NDEBUG and its
// class layout depends on that macro, so this file is compiled without it;
// Simbody's own assertions stay on inside the library, and its times include
// them.
#include <Simbody.h>

#include <functional>
#include <iostream>
#include <memory>

#include "peer_common.hpp"

using namespace SimTK;

namespace {

struct integrator_kind {
  const char* name;
  std::function<std::unique_ptr<Integrator>(const MultibodySystem&)> make;
};

void study(const std::string& name, const peer::reference& ref, bool quick) {
  MultibodySystem system;
  SimbodyMatterSubsystem matter(system);
  GeneralForceSubsystem forces(system);
  Force::UniformGravity gravity(forces, matter, Vec3(0, -peer::g, 0));
  std::vector<MobilizedBody> joints;
  if (name == "robot_arm") {
    const Vec3 c(peer::arm_d, 0, 0);
    const Body::Rigid body(MassProperties(
        peer::arm_m, c, Inertia(Vec3(peer::arm_Jx, peer::arm_Jz, peer::arm_Jz)).shiftFromMassCenter(-c, peer::arm_m)));
    joints.push_back(MobilizedBody::Pin(matter.Ground(), Transform(), body, Transform()));
  } else if (name == "fourbar") {
    // Three Pins in a chain and a Ball constraint pinning the rocker's end to
    // the ground (its z row is redundant in this planar loop; Simbody's
    // projection takes redundant constraints).
    auto bar = [](double L, double m) {
      const Vec3 c(L / 2, 0, 0);
      const double I = m * L * L / 12;
      return Body::Rigid(MassProperties(m, c, Inertia(Vec3(1e-3 * I, I, I)).shiftFromMassCenter(-c, m)));
    };
    MobilizedBody::Pin crank(matter.Ground(), Transform(), bar(peer::fourbar_a, peer::fourbar_ma), Transform());
    MobilizedBody::Pin coupler(crank, Transform(Vec3(peer::fourbar_a, 0, 0)), bar(peer::fourbar_b, peer::fourbar_mb),
                               Transform());
    MobilizedBody::Pin rocker(coupler, Transform(Vec3(peer::fourbar_b, 0, 0)), bar(peer::fourbar_c, peer::fourbar_mc),
                              Transform());
    Constraint::Ball(rocker, Vec3(peer::fourbar_c, 0, 0), matter.Ground(), Vec3(peer::fourbar_d, 0, 0));
    joints = {crank, coupler, rocker};
  } else {
    const Body::Rigid cart(MassProperties(peer::crane_M, Vec3(0), Inertia(0.1 * peer::crane_M)));
    const Vec3 c(peer::crane_d, 0, 0);
    const Body::Rigid load(MassProperties(peer::crane_m, c, Inertia(0).shiftFromMassCenter(-c, peer::crane_m)));
    MobilizedBody::Slider rail(matter.Ground(), Transform(), cart, Transform());
    joints.push_back(rail);
    joints.push_back(MobilizedBody::Pin(rail, Transform(), load, Transform()));
  }
  system.realizeTopology();
  const int nq = static_cast<int>(joints.size());
  State s0 = system.getDefaultState();
  for (int i = 0; i < nq; ++i) {
    joints[i].setOneQ(s0, 0, ref.x0[i]);
    joints[i].setOneU(s0, 0, ref.x0[nq + i]);
  }

  const integrator_kind kinds[] = {
      {"simbody: RungeKuttaMerson",
       [](const MultibodySystem& s) { return std::make_unique<RungeKuttaMersonIntegrator>(s); }},
      {"simbody: RungeKuttaFeldberg",
       [](const MultibodySystem& s) { return std::make_unique<RungeKuttaFeldbergIntegrator>(s); }},
      {"simbody: RungeKutta3", [](const MultibodySystem& s) { return std::make_unique<RungeKutta3Integrator>(s); }},
      {"simbody: Verlet", [](const MultibodySystem& s) { return std::make_unique<VerletIntegrator>(s); }},
      {"simbody: CPodes (BDF)", [](const MultibodySystem& s) { return std::make_unique<CPodesIntegrator>(s); }},
  };
  for (const auto& k : kinds) {
    for (int e = 3; e <= 12; e += quick ? 3 : 1) {
      const double tol = std::pow(10.0, -e);
      long evals = 0, steps = 0, rejected = 0;
      std::vector<double> x(2 * nq);
      auto run = [&] {
        auto integ = k.make(system);
        integ->setAccuracy(tol);
        integ->setAllowInterpolation(false);  // land on T, as flange's runs do
        integ->setMaximumStepSize(1.0);
        integ->setInternalStepLimit(100000000);  // CPodes stops at 500 steps a call by default
        TimeStepper ts(system, *integ);
        ts.initialize(s0);
        ts.stepTo(ref.T);
        const State& s = integ->getState();
        for (int i = 0; i < nq; ++i) {
          x[i] = joints[i].getOneQ(s, 0);
          x[nq + i] = joints[i].getOneU(s, 0);
        }
        evals = integ->getNumRealizations();
        steps = integ->getNumStepsTaken();
        rejected = integ->getNumStepsAttempted() - steps;
      };
      try {
        run();
      } catch (const std::exception& ex) {
        std::printf("simbody: %s at accuracy %g failed: %s\n", k.name, tol, ex.what());
        continue;
      }
      const double err = peer::scaled_error(x, ref.x);
      if (!(err <= 1)) continue;
      const double sec = peer::median_seconds(run, quick ? 3 : 5, quick ? 5e-4 : 3e-3) / ref.T;
      peer::print_row(name, k.name, "tol", tol, err, sec, evals, steps, rejected);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  peer::options o;
  if (!peer::parse(argc, argv, o)) {
    std::cerr << "usage: simbody_peer --reference FILE [--quick] [--scene NAME]\n";
    return 2;
  }
  std::printf("Simbody 3.7 (Debian's libsimbody, built with its assertions on): accuracy sweep per integrator\n");
  const auto refs = peer::read_references(o.reference, {{"robot_arm", 2}, {"gantry_crane", 4}, {"fourbar", 6}});
  for (const char* name : {"robot_arm", "gantry_crane", "fourbar"}) {
    if (!o.scene.empty() && o.scene != name) continue;
    const auto r = refs.find(name);
    if (r == refs.end()) {
      std::printf("simbody: no reference for %s in %s\n", name, o.reference.c_str());
      continue;
    }
    study(name, r->second, o.quick);
  }
  return 0;
}
