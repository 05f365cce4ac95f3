// Simbody on the paper's robot arm and gantry crane, a free body, a
// floating-base robot with four legs, and a four-bar (a closed loop: a Ball constraint, projected by Simbody), measured the way
// benchmarks/work_precision.cpp measures flange: the scaled error at T against
// flange's long-double reference, and the median wall time per simulated
// second, over a sweep of accuracies for each of Simbody's integrators.
//
//   simbody_peer --reference FILE [--quick] [--scene NAME]
//
// The models match flange's (peer_common.hpp): a Pin (rotation about z, or
// about y or x with its frames turned), a Slider (translation along x) and a
// Free mobilizer (its quaternion and ω mapped to flange's FreeMotion state on
// the way in and out), the mass properties at the same places, uniform
// gravity along −y and no other force.
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
  // A free base's state is not one q and one u per joint (below).
  std::unique_ptr<MobilizedBody::Free> free;
  auto free_base = [&](const MassProperties& mp) {
    free = std::make_unique<MobilizedBody::Free>(matter.Ground(), Transform(), Body::Rigid(mp), Transform());
  };
  if (name == "free_body") {
    const Vec3 c(peer::free_cm, 0, 0);
    free_base(MassProperties(
        peer::free_m, c,
        Inertia(Vec3(peer::free_J[0], peer::free_J[1], peer::free_J[2])).shiftFromMassCenter(-c, peer::free_m)));
  } else if (name == "legged") {
    // models::legged<4, 3>(): the trunk on the Free mobilizer; per leg a Pin
    // at the hip about y, then two about x, each link's body at its joint
    // with its centre of mass at mid-link. A Pin turns about its frames' z,
    // so both of its frames are turned to bring z onto the joint's axis.
    free_base(MassProperties(peer::legged_trunk_m, Vec3(0),
                             Inertia(Vec3(peer::legged_trunk_J[0], peer::legged_trunk_J[1], peer::legged_trunk_J[2]))));
    const Vec3 c(0, -0.5 * peer::legged_link_L, 0);
    const Body::Rigid link(MassProperties(
        peer::legged_link_m, c,
        Inertia(Vec3(peer::legged_link_J[0], peer::legged_link_J[1], peer::legged_link_J[2]))
            .shiftFromMassCenter(-c, peer::legged_link_m)));
    const Rotation z_to_y(-Pi / 2, XAxis), z_to_x(Pi / 2, YAxis);
    for (int k = 0; k < 4; ++k) {
      const double sx = (k % 2 ? -1 : 1) * peer::legged_hip_x, sz = (k / 2 ? -1 : 1) * peer::legged_hip_z;
      MobilizedBody parent = *free;
      for (int j = 0; j < 3; ++j) {
        const Rotation& R = j == 0 ? z_to_y : z_to_x;
        const Vec3 at = j == 0 ? Vec3(sx, 0, sz) : Vec3(0, -peer::legged_link_L, 0);
        MobilizedBody::Pin pin(parent, Transform(R, at), link, Transform(R));
        joints.push_back(pin);
        parent = pin;
      }
    }
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
  // flange's state: q = (the free base's 7, one per joint), then v = (the
  // free base's 6, one per joint). A free base's q is (r, Qx, Qy, Qz, Qw) and
  // its v is (v, ω in body axes); Simbody's Free mobilizer has
  // q = (Qw, Qx, Qy, Qz, r) and u = (ω, v), both vectors in the ground frame.
  const int nj = static_cast<int>(joints.size()), fq = free ? 7 : 0, fu = free ? 6 : 0;
  const int nq = fq + nj, n_state = nq + fu + nj;
  State s0 = system.getDefaultState();
  {
    const std::vector<double>& x = ref.x0;
    if (free) {
      const Quaternion Q(Vec4(x[6], x[3], x[4], x[5]));
      free->setQToFitTransform(s0, Transform(Rotation(Q), Vec3(x[0], x[1], x[2])));
      const Vec3 w_world = Rotation(Q) * Vec3(x[nq + 3], x[nq + 4], x[nq + 5]);
      free->setUToFitVelocity(s0, SpatialVec(w_world, Vec3(x[nq], x[nq + 1], x[nq + 2])));
    }
    for (int i = 0; i < nj; ++i) {
      joints[i].setOneQ(s0, 0, x[fq + i]);
      joints[i].setOneU(s0, 0, x[nq + fu + i]);
    }
  }
  auto read_state = [&](const State& s, std::vector<double>& x) {
    if (free) {
      const Vec7 q = free->getQ(s);  // integrated as it is, so its sign is the reference's
      const Vec6 u = free->getU(s);
      const Quaternion Q(Vec4(q[0], q[1], q[2], q[3]));
      const Vec3 w_body = ~Rotation(Q) * Vec3(u[0], u[1], u[2]);
      const double fx[] = {q[4], q[5], q[6], q[1], q[2], q[3], q[0]};
      for (int i = 0; i < 7; ++i) x[i] = fx[i];
      for (int i = 0; i < 3; ++i) {
        x[nq + i] = u[3 + i];
        x[nq + 3 + i] = w_body[i];
      }
    }
    for (int i = 0; i < nj; ++i) {
      x[fq + i] = joints[i].getOneQ(s, 0);
      x[nq + fu + i] = joints[i].getOneU(s, 0);
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
      if (peer::quick_sweep_done(quick, evals)) break;
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
      peer::read_references(o.reference, {{"robot_arm", 2}, {"gantry_crane", 4}, {"free_body", 13}, {"legged", 37}, {"fourbar", 6}});
  for (const char* name : {"robot_arm", "gantry_crane", "free_body", "legged", "fourbar"}) {
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
