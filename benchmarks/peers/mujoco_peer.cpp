// MuJoCo on the paper's robot arm and gantry crane, a free body, a
// floating-base robot with four legs and a four-bar (a closed loop, held by
// MuJoCo's soft equality constraint), measured the way
// benchmarks/work_precision.cpp measures flange: the scaled error at T against
// flange's long-double reference, and the median wall time per simulated
// second, over a sweep of time steps for each of MuJoCo's integrators.
//
//   mujoco_peer --reference FILE [--quick] [--scene NAME]
//
// The models match flange's (peer_common.hpp): a hinge about z and a slide
// along x, the inertial properties at the same places, gravity along −y,
// armature and damping 0, contacts and (but for the four-bar's loop) every
// constraint off. The motor torque
// and the cart force are actuators whose controls are set in mjcb_control, so
// an input would be seen at every RK4 stage; both inputs are 0 here, as in
// flange's study.
//
// A free joint's state is flange's FreeMotion's, but for the quaternion's
// order: MuJoCo's qpos holds (w, x, y, z), flange's (x, y, z, w); both take
// the linear velocity in the world and ω in body axes. The states are mapped
// on the way in and out.
//
// One difference remains: MuJoCo refuses a moving body without rotational
// inertia ("mass and inertia of moving bodies must be larger than mjMINVAL"),
// so the crane's point-mass load gets 1e-14 kg m², which changes the
// pendulum's inertia m·d² = 0.5 kg m² by 2e-14 relative: below every error
// measured here.
//
// MuJoCo's integrators: RK4 (4 evaluations a step), semi-implicit Euler and
// implicit-in-velocity Euler (1 each). All are fixed-step.
#include <mujoco/mujoco.h>

#include <cstring>
#include <iostream>
#include <memory>

#include "mujoco_models.hpp"
#include "peer_common.hpp"

namespace {

std::string arm_xml() {
  std::ostringstream x;
  x << "<mujoco model='robot_arm'><compiler angle='radian'/>"
    << "<option gravity='0 " << -peer::g << " 0'><flag contact='disable' constraint='disable'/></option>"
    << "<worldbody><body name='arm'>"
    << "<joint name='joint' type='hinge' axis='0 0 1' armature='0' damping='0' limited='false'/>"
    << "<inertial pos='" << peer::arm_d << " 0 0' mass='" << peer::arm_m << "' diaginertia='" << peer::arm_Jx << ' '
    << peer::arm_Jz << ' ' << peer::arm_Jz << "'/>"
    << "</body></worldbody>"
    << "<actuator><motor name='motor' joint='joint' gear='1'/></actuator></mujoco>";
  return x.str();
}

std::string crane_xml() {
  std::ostringstream x;
  x << "<mujoco model='gantry_crane'><compiler angle='radian'/>"
    << "<option gravity='0 " << -peer::g << " 0'><flag contact='disable' constraint='disable'/></option>"
    << "<worldbody><body name='cart'>"
    << "<joint name='rail' type='slide' axis='1 0 0' armature='0' damping='0' limited='false'/>"
    << "<inertial pos='0 0 0' mass='" << peer::crane_M << "' diaginertia='" << 0.1 * peer::crane_M << ' '
    << 0.1 * peer::crane_M << ' ' << 0.1 * peer::crane_M << "'/>"
    << "<body name='load'>"
    << "<joint name='pivot' type='hinge' axis='0 0 1' armature='0' damping='0' limited='false'/>"
    << "<inertial pos='" << peer::crane_d << " 0 0' mass='" << peer::crane_m << "' diaginertia='1e-14 1e-14 1e-14'/>"
    << "</body></body></worldbody>"
    << "<actuator><motor name='force' joint='rail' gear='1'/></actuator></mujoco>";
  return x.str();
}

std::string free_body_xml() {
  std::ostringstream x;
  x << "<mujoco model='free_body'><compiler angle='radian'/>"
    << "<option gravity='0 " << -peer::g << " 0'><flag contact='disable' constraint='disable'/></option>"
    << "<worldbody><body name='body'><freejoint/>"
    << "<inertial pos='" << peer::free_cm << " 0 0' mass='" << peer::free_m << "' diaginertia='" << peer::free_J[0]
    << ' ' << peer::free_J[1] << ' ' << peer::free_J[2] << "'/>"
    << "</body></worldbody></mujoco>";
  return x.str();
}

/// The four-bar: three hinges about z in a chain, and an equality
/// constraint ("connect") pinning the rocker's end to the world. MuJoCo's
/// constraints are soft (its default solref 0.02 s, solimp): the loop is
/// held by a stiff damped spring, not exactly. A connect's world anchor is
/// where the rocker's end is at qpos0, so the bodies are drawn at the closed
/// initial configuration x0 with each hinge's ref at its angle there: qpos
/// is then flange's q.
std::string fourbar_xml(const std::vector<double>& x0) {
  auto bar = [](double L, double m) {
    std::ostringstream b;
    const double I = m * L * L / 12;
    b << "<inertial pos='" << L / 2 << " 0 0' mass='" << m << "' diaginertia='" << 1e-3 * I << ' ' << I << ' ' << I
      << "'/>";
    return b.str();
  };
  auto hinge = [](double ref) {
    std::ostringstream h;
    h.precision(17);
    h << "<joint type='hinge' axis='0 0 1' ref='" << ref << "' armature='0' damping='0' limited='false'/>";
    return h.str();
  };
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco model='fourbar'><compiler angle='radian'/>"
    << "<option gravity='0 " << -peer::g << " 0'><flag contact='disable'/></option><worldbody>"
    << "<body name='crank' euler='0 0 " << x0[0] << "'>" << hinge(x0[0]) << bar(peer::fourbar_a, peer::fourbar_ma)
    << "<body name='coupler' pos='" << peer::fourbar_a << " 0 0' euler='0 0 " << x0[1] << "'>" << hinge(x0[1])
    << bar(peer::fourbar_b, peer::fourbar_mb) << "<body name='rocker' pos='" << peer::fourbar_b << " 0 0' euler='0 0 "
    << x0[2] << "'>" << hinge(x0[2]) << bar(peer::fourbar_c, peer::fourbar_mc)
    << "</body></body></body></worldbody>"
    << "<equality><connect body1='rocker' body2='world' anchor='" << peer::fourbar_c << " 0 0'/></equality></mujoco>";
  return x.str();
}


/// The inputs, set where MuJoCo reads them at every stage of a step.
void control(const mjModel* m, mjData* d) {
  for (int i = 0; i < m->nu; ++i) d->ctrl[i] = 0.0;  // the study's inputs are 0
}

void study(const std::string& name, const std::string& xml, const peer::reference& ref, bool quick) {
  mjModel* m = peer::load(xml);
  if (!m) return;
  mjData* d = mj_makeData(m);
  if (static_cast<std::size_t>(m->nq + m->nv) != ref.x0.size()) {
    std::printf("mujoco: %s has %d + %d state variables, flange's reference %zu\n", name.c_str(), m->nq, m->nv,
                ref.x0.size());
    mj_deleteData(d);
    mj_deleteModel(m);
    return;
  }
  struct integrator {
    const char* name;
    int kind, evals_per_step;
    double dt_max, dt_min;
  };
  const integrator integrators[] = {{"mujoco: RK4", mjINT_RK4, 4, 1e-1, 1e-4},
                                    {"mujoco: semi-implicit Euler", mjINT_EULER, 1, 1e-2, 1e-5},
                                    {"mujoco: implicit Euler", mjINT_IMPLICIT, 1, 1e-2, 1e-5}};
  const double factor = quick ? 10.0 : std::sqrt(10.0);
  for (const auto& in : integrators) {
    m->opt.integrator = in.kind;
    for (double dt = in.dt_max; dt >= in.dt_min * 0.999; dt /= factor) {
      const long n = std::max(1L, std::lround(ref.T / dt));
      m->opt.timestep = ref.T / n;
      auto run = [&] {
        mj_resetData(m, d);
        peer::to_mujoco(m, ref.x0, d);
        for (long k = 0; k < n; ++k) mj_step(m, d);
      };
      run();
      const double e = peer::scaled_error(peer::from_mujoco(m, d), ref.x);
      if (!(e <= 1)) continue;  // diverged: left out, as flange's runs are
      const double sec = peer::median_seconds(run, quick ? 3 : 5, quick ? 5e-4 : 3e-3) / ref.T;
      peer::print_row(name, in.name, "dt", ref.T / n, e, sec, n * in.evals_per_step, n, 0);
      if (peer::quick_sweep_done(quick, n * in.evals_per_step)) break;
    }
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace

int main(int argc, char** argv) {
  peer::options o;
  if (!peer::parse(argc, argv, o)) {
    std::cerr << "usage: mujoco_peer --reference FILE [--quick] [--scene NAME]\n";
    return 2;
  }
  std::printf("MuJoCo %s (Debian's libmujoco): RK4, semi-implicit and implicit Euler over a time-step sweep\n",
              mj_versionString());
  mjcb_control = control;
  const auto refs = peer::read_references(
      o.reference, {{"robot_arm", 2}, {"gantry_crane", 4}, {"free_body", 13}, {"legged", 37}, {"fourbar", 6}});
  for (const auto& [name, xml] : {std::pair{std::string("robot_arm"), arm_xml()},
                                  {"gantry_crane", crane_xml()},
                                  {"free_body", free_body_xml()},
                                  {"legged", peer::legged_xml(4, 3)},
                                  {"fourbar", std::string()}}) {
    if (!o.scene.empty() && o.scene != name) continue;
    const auto r = refs.find(name);
    if (r == refs.end()) {
      std::printf("mujoco: no reference for %s in %s\n", name.c_str(), o.reference.c_str());
      continue;
    }
    study(name, name == "fourbar" ? fourbar_xml(r->second.x0) : xml, r->second, o.quick);
  }
  return 0;
}
