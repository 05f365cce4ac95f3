// Simbody on the paper's robot arm and gantry crane, a free body, and a
// four-bar (a closed loop: a Ball constraint, projected by Simbody), measured the way
// benchmarks/work_precision.cpp measures flange: the scaled error at T against
// flange's long-double reference, and the median wall time per simulated
// second, over a sweep of accuracies for each of Simbody's integrators.
//
//   simbody_peer --reference FILE [--quick] [--scene NAME]
//
// The models match flange's (peer_common.hpp): a Pin (rotation about z), a
// Slider (translation along x) and a Free mobilizer (its quaternion and
// ω mapped to flange's FreeMotion state on the way in and out), the mass
// properties at the same places, uniform gravity along −y and no other force.
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
  // A free body's state is not one q and one u per joint (below).
  std::unique_ptr<MobilizedBody::Free> free;
  if (name == "free_body") {
    const Vec3 c(peer::free_cm, 0, 0);
    const Body::Rigid body(MassProperties(
        peer::free_m, c,
        Inertia(Vec3(peer::free_J[0], peer::free_J[1], peer::free_J[2])).shiftFromMassCenter(-c, peer::free_m)));
    free = std::make_unique<MobilizedBody::Free>(matter.Ground(), Transform(), body, Transform());
  } else if (name == "robot_arm") {
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
  // The free body: flange's x = (r, Qx, Qy, Qz, Qw, v, ω in body axes);
  // Simbody's Free mobilizer has q = (Qw, Qx, Qy, Qz, r) and u = (ω, v), both
  // vectors in the ground frame.
  if (free) {
    const std::vector<double>& x = ref.x0;
    const Quaternion Q(Vec4(x[6], x[3], x[4], x[5]));
    free->setQToFitTransform(s0, Transform(Rotation(Q), Vec3(x[0], x[1], x[2])));
    const Vec3 w_world = Rotation(Q) * Vec3(x[10], x[11], x[12]);
    free->setUToFitVelocity(s0, SpatialVec(w_world, Vec3(x[7], x[8], x[9])));
  }
  const std::size_t n_state = free ? 13 : 2 * nq;
  auto read_state = [&](const State& s, std::vector<double>& x) {
    if (free) {
      const Vec7 q = free->getQ(s);  // (Qw, Qx, Qy, Qz, r), integrated as it is: its sign is kept
      const Vec6 u = free->getU(s);
      const Quaternion Q(Vec4(q[0], q[1], q[2], q[3]));
      const Vec3 w_body = ~Rotation(Q) * Vec3(u[0], u[1], u[2]);
      x = {q[4], q[5], q[6], q[1], q[2], q[3], q[0], u[3], u[4], u[5], w_body[0], w_body[1], w_body[2]};
      return;
    }
    for (int i = 0; i < nq; ++i) {
      x[i] = joints[i].getOneQ(s, 0);
      x[nq + i] = joints[i].getOneU(s, 0);
    }
  };

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
      std::vector<double> x(n_state);
      auto run = [&] {
        auto integ = k.make(system);
        integ->setAccuracy(tol);
        integ->setAllowInterpolation(false);  // land on T, as flange's runs do
        integ->setMaximumStepSize(1.0);
        integ->setInternalStepLimit(100000000);  // CPodes stops at 500 steps a call by default
        TimeStepper ts(system, *integ);
        ts.initialize(s0);
        ts.stepTo(ref.T);
        read_state(integ->getState(), x);
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
  const auto refs =
      peer::read_references(o.reference, {{"robot_arm", 2}, {"gantry_crane", 4}, {"free_body", 13}, {"fourbar", 6}});
  for (const char* name : {"robot_arm", "gantry_crane", "free_body", "fourbar"}) {
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
