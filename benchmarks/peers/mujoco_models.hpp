// MuJoCo models of flange's scenes, built as MJCF text from the same
// parameters, and the state mapping between the two. Shared by the peer
// work-precision program (mujoco_peer.cpp) and the scale benchmark
// (benchmarks/scale.cpp). Plain C++17 and MuJoCo's C API, no flange header.
#pragma once
#include <mujoco/mujoco.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "peer_common.hpp"

namespace peer {

/// models::legged<Legs, Links>(): a trunk on a free joint, Legs legs of Links
/// hinges (the hip about y, the others about x), each link a body at its end
/// with its centre of mass at mid-link.
inline std::string legged_xml(int legs, int links) {
  std::ostringstream x;
  x << "<mujoco model='legged'><compiler angle='radian'/>"
    << "<option gravity='0 " << -peer::g << " 0'><flag contact='disable' constraint='disable'/></option>"
    << "<worldbody><body name='trunk'><freejoint/>"
    << "<inertial pos='0 0 0' mass='" << peer::legged_trunk_m << "' diaginertia='" << peer::legged_trunk_J[0] << ' '
    << peer::legged_trunk_J[1] << ' ' << peer::legged_trunk_J[2] << "'/>";
  for (int k = 0; k < legs; ++k) {
    const double sx = (k % 2 ? -1 : 1) * peer::legged_hip_x, sz = (k / 2 ? -1 : 1) * peer::legged_hip_z;
    for (int j = 0; j < links; ++j) {
      x << "<body pos='";
      if (j == 0) x << sx << " 0 " << sz;
      else x << "0 " << -peer::legged_link_L << " 0";
      x << "'><joint type='hinge' axis='" << (j == 0 ? "0 1 0" : "1 0 0")
        << "' armature='0' damping='0' limited='false'/>"
        << "<inertial pos='0 " << -0.5 * peer::legged_link_L << " 0' mass='" << peer::legged_link_m
        << "' diaginertia='" << peer::legged_link_J[0] << ' ' << peer::legged_link_J[1] << ' ' << peer::legged_link_J[2]
        << "'/>";
    }
    for (int j = 0; j < links; ++j) x << "</body>";
  }
  x << "</body></worldbody></mujoco>";
  return x.str();
}

/// models::chain<N>(p) with run-time or coordinate axes: body L sits at the
/// previous link's offset d, turns about its hinge axis n, and has mass m at d
/// with diagonal inertia J about it. All numbers to 17 digits.
inline std::string chain_xml(const std::vector<std::array<double, 3>>& axis, const std::vector<std::array<double, 3>>& d,
                             const std::vector<double>& m, const std::vector<std::array<double, 3>>& J,
                             const std::array<double, 3>& g) {
  std::ostringstream x;
  x.precision(17);
  auto v3 = [&](const std::array<double, 3>& a) {
    std::ostringstream o;
    o.precision(17);
    o << a[0] << ' ' << a[1] << ' ' << a[2];
    return o.str();
  };
  x << "<mujoco model='chain'><compiler angle='radian'/>"
    << "<option gravity='" << v3(g) << "'><flag contact='disable' constraint='disable'/></option><worldbody>";
  for (std::size_t i = 0; i < m.size(); ++i) {
    x << "<body pos='" << (i == 0 ? std::string("0 0 0") : v3(d[i - 1])) << "'>"
      << "<joint type='hinge' axis='" << v3(axis[i]) << "' armature='0' damping='0' limited='false'/>"
      << "<inertial pos='" << v3(d[i]) << "' mass='" << m[i] << "' diaginertia='" << v3(J[i]) << "'/>";
  }
  for (std::size_t i = 0; i < m.size(); ++i) x << "</body>";
  x << "</worldbody></mujoco>";
  return x.str();
}

/// flange's state (q, v) to MuJoCo's qpos, qvel and back: the same but for a
/// free joint's quaternion, (x, y, z, w) in flange and (w, x, y, z) in MuJoCo.
inline void to_mujoco(const mjModel* m, const std::vector<double>& x, mjData* d) {
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = x[i];
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = x[m->nq + i];
  for (int j = 0; j < m->njnt; ++j)
    if (m->jnt_type[j] == mjJNT_FREE) {
      const int a = m->jnt_qposadr[j] + 3;
      d->qpos[a] = x[a + 3];
      for (int c = 0; c < 3; ++c) d->qpos[a + 1 + c] = x[a + c];
    }
}
inline std::vector<double> from_mujoco(const mjModel* m, const mjData* d) {
  std::vector<double> x(m->nq + m->nv);
  for (int i = 0; i < m->nq; ++i) x[i] = d->qpos[i];
  for (int i = 0; i < m->nv; ++i) x[m->nq + i] = d->qvel[i];
  for (int j = 0; j < m->njnt; ++j)
    if (m->jnt_type[j] == mjJNT_FREE) {
      const int a = m->jnt_qposadr[j] + 3;
      x[a + 3] = d->qpos[a];
      for (int c = 0; c < 3; ++c) x[a + c] = d->qpos[a + 1 + c];
    }
  return x;
}

inline mjModel* load(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();  // large: keep it off the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), "scene.xml", static_cast<int>(xml.size())) != 0) return nullptr;
  std::memcpy(vfs->filedata[vfs->nfile - 1], xml.data(), xml.size());
  char err[1000] = "";
  mjModel* m = mj_loadXML("scene.xml", vfs.get(), err, sizeof err);
  if (!m) std::printf("mujoco: %s\n", err);
  mj_deleteVFS(vfs.get());
  return m;
}

}  // namespace peer
