// URDF import checked against an independent implementation: MuJoCo 2.2.2
// loads the same URDF files that flange-urdf turned into the scenes included
// here (tests/urdf/). At 100 random states each, flange's q̈ = f(q, q̇, τ)
// equals MuJoCo's to 1e-9 relative: with τ = 0 (gravity, Coriolis, damping)
// and with random joint forces, and the mass matrices agree.
//
// MuJoCo runs with contacts, joint limits and every other constraint off;
// its limits are soft constraints, flange's compliant stops (flange-urdf
// turns <limit> into them), so states are drawn inside the limits, where
// neither acts (stops_test.cpp checks the stops against Simbody's). Joints are
// matched by name; a free joint's quaternion is (w, x, y, z) in MuJoCo and
// (x, y, z, w) in flange, and both take its linear velocity in the world
// and ω in body axes.
//
// One difference is numerical and MuJoCo's own: it stores each body's
// inertia as principal moments and axes from its iterative eigen-solver
// (mju_eig3), which stops early: for an inertia with two or three products
// of inertia its reconstruction is off by up to ~3e-10 kg·m² (1e-8
// relative), the same whether the inertia comes from a URDF or from MJCF's
// fullinertia. That moves q̈ by 1e-8 on arm6. So the check has two steps:
// 1. MuJoCo's inertias as it read them from the URDF (origins, rpy and all)
//    equal flange's, body by body, to within twice MuJoCo's own error on
//    the same matrix given directly as MJCF fullinertia (measured here);
// 2. an exact principal-axis decomposition (Eigen's) of those inertias
//    replaces MuJoCo's, and q̈ must agree to 1e-9.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#include "arm6.hpp"
#include "com_at_origin.hpp"
#include "floating_legs.hpp"
#include "legs_fixed_root.hpp"
#include "two_link_planar.hpp"

namespace {

struct mujoco_model {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit mujoco_model(const std::string& file) {
    char err[1000] = "";
    m = mj_loadXML(file.c_str(), nullptr, err, sizeof err);
    if (!m) FAIL("MuJoCo could not load " << file << ": " << err);
    m->opt.disableflags |= mjDSBL_CONSTRAINT | mjDSBL_CONTACT;
    d = mj_makeData(m);
  }
  ~mujoco_model() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  mujoco_model(const mujoco_model&) = delete;
  mujoco_model& operator=(const mujoco_model&) = delete;
};

/// flange's state from MuJoCo's (qpos, qvel), joint by joint, by name.
template <class S>
typename S::state_type from_mujoco(const mjModel* m, const mjData* d) {
  typename S::state_type x{};
  for (int j = 0; j < m->njnt; ++j) {
    const std::string name = mj_id2name(m, mjOBJ_JOINT, j);
    const int qa = m->jnt_qposadr[j], va = m->jnt_dofadr[j];
    const int q = S::q_offset(name), v = S::n_q + S::v_offset(name);
    REQUIRE(S::index_of(name) >= 0);
    if (m->jnt_type[j] == mjJNT_FREE) {
      REQUIRE(S::table.nq[S::index_of(name)] == 7);
      if constexpr (S::n_q == S::n_v) return x;  // no quaternion in S: not reached
      double* xq = x.data() + q;
      double* xv = x.data() + v;
      for (int i = 0; i < 3; ++i) xq[i] = d->qpos[qa + i];
      for (int i = 0; i < 3; ++i) xq[3 + i] = d->qpos[qa + 4 + i];  // x, y, z
      xq[6] = d->qpos[qa + 3];                                        // w
      for (int i = 0; i < 6; ++i) xv[i] = d->qvel[va + i];
    } else {
      x[q] = d->qpos[qa];
      x[v] = d->qvel[va];
    }
  }
  return x;
}

/// A random state in MuJoCo: angles and slides, unit quaternions, rates.
void random_state(const mjModel* m, mjData* d, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (int j = 0; j < m->njnt; ++j) {
    const int qa = m->jnt_qposadr[j], va = m->jnt_dofadr[j];
    if (m->jnt_type[j] == mjJNT_FREE) {
      for (int i = 0; i < 3; ++i) d->qpos[qa + i] = u(rng);
      Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
      quat.normalize();
      for (int i = 0; i < 4; ++i) d->qpos[qa + 3 + i] = quat[i];
      for (int i = 0; i < 6; ++i) d->qvel[va + i] = 2 * u(rng);
    } else {
      d->qpos[qa] = m->jnt_type[j] == mjJNT_SLIDE ? 0.2 * u(rng) : 3.1 * u(rng);
      // Inside a limited joint's range, where flange's stops (flange-urdf
      // turns <limit> into them) push nothing, as MuJoCo's limits are off.
      if (m->jnt_limited[j]) {
        const double lo = m->jnt_range[2 * j], hi = m->jnt_range[2 * j + 1];
        d->qpos[qa] = 0.5 * (lo + hi) + 0.49 * (hi - lo) * u(rng);
      }
      d->qvel[va] = 2 * u(rng);
    }
  }
}

/// max |a − b| / max(1, max |b|) over the rates.
template <class A>
double relative_difference(const A& a, const double* b, int n) {
  double diff = 0, scale = 1;
  for (int i = 0; i < n; ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return diff / scale;
}

/// MuJoCo's inertia for a body given J directly (MJCF fullinertia): what its
/// eigen-solver gives back, R·diag·Rᵀ.
Eigen::Matrix3d mujoco_inertia(const mjModel* m, int b) {
  const Eigen::Quaterniond iq(m->body_iquat[4 * b], m->body_iquat[4 * b + 1], m->body_iquat[4 * b + 2],
                              m->body_iquat[4 * b + 3]);
  const Eigen::Matrix3d R = iq.normalized().toRotationMatrix();
  return R *
         Eigen::Vector3d(m->body_inertia[3 * b], m->body_inertia[3 * b + 1], m->body_inertia[3 * b + 2]).asDiagonal() *
         R.transpose();
}
double mujoco_own_error(const Eigen::Matrix3d& J) {
  char xml[600], err[500];
  std::snprintf(xml, sizeof xml,
                "<mujoco><worldbody><body><joint type='hinge'/><inertial pos='0 0 0' mass='1' "
                "fullinertia='%.17g %.17g %.17g %.17g %.17g %.17g'/></body></worldbody></mujoco>",
                J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2));
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  mj_makeEmptyFileVFS(&vfs, "inertia.xml", int(sizeof xml));
  const int f = mj_findFileVFS(&vfs, "inertia.xml");
  std::memcpy(vfs.filedata[f], xml, std::strlen(xml) + 1);
  vfs.filesize[f] = int(std::strlen(xml));
  mjModel* m = mj_loadXML("inertia.xml", &vfs, err, sizeof err);
  REQUIRE(m);
  const double e = (mujoco_inertia(m, 1) - J).norm();
  mj_deleteModel(m);
  mj_deleteVFS(&vfs);
  return e;
}

/// Compares MuJoCo's body inertias with flange's Bodies of the same names
/// (returns the largest relative difference), then gives MuJoCo an exact
/// principal-axis decomposition of flange's.
template <class S>
double match_inertias(const S& scene, mjModel* m, mjData* d) {
  double worst = 0;
  int matched = 0;
  flange::detail::for_each_component(scene, [&](auto, const auto& c) {
    using C = std::remove_cvref_t<decltype(c)>;
    if constexpr (C::kind == flange::role::body) {
      const int b = mj_name2id(m, mjOBJ_BODY, std::string(C::name.view()).c_str());
      REQUIRE(b > 0);
      ++matched;
      const Eigen::Matrix3d J_mj = mujoco_inertia(m, b);
      const Eigen::Vector3d c_mj(m->body_ipos[3 * b], m->body_ipos[3 * b + 1], m->body_ipos[3 * b + 2]);
      CHECK(m->body_mass[b] == Approx(c.m()).epsilon(1e-15));
      CHECK((c_mj - c.r_cm()).norm() <= 1e-15);
      const double diff = (J_mj - c.J()).norm(), own = mujoco_own_error(c.J());
      INFO("body " << C::name.view() << ": |J_MuJoCo − J_flange| = " << diff << ", MuJoCo's own error " << own);
      CHECK(diff <= 2 * own + 1e-14 * c.J().norm());
      worst = std::max(worst, diff / c.J().norm());
      // The exact decomposition: J = V·Λ·Vᵀ with V a rotation.
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c.J());
      Eigen::Matrix3d V = eig.eigenvectors();
      if (V.determinant() < 0) V.col(2) = -V.col(2);
      const Eigen::Quaterniond q(V);
      const double quat[4] = {q.w(), q.x(), q.y(), q.z()};
      for (int i = 0; i < 4; ++i) m->body_iquat[4 * b + i] = quat[i];
      for (int i = 0; i < 3; ++i) m->body_inertia[3 * b + i] = eig.eigenvalues()[i];
      // MuJoCo skips iquat and ipos for a body whose inertial frame it found to
      // be its own frame (body_sameframe, set at load: a centre of mass at the
      // origin and the principal axes along the body's), and takes such a body
      // as simple. The principal axes handed over here need not be the body's
      // (Eigen orders the moments): say so, or MuJoCo reads the moments along
      // the wrong axes (30 % off in q̈ for com_at_origin.urdf).
      const bool same = c_mj.norm() == 0 && V.isIdentity(0);
      m->body_sameframe[b] = same ? 1 : 0;
      if (!same) m->body_simple[b] = 0;
    }
  });
  REQUIRE(matched > 0);
  mj_setConst(m, d);
  return worst;
}

template <class S>
void check_against_mujoco(const S& scene, const std::string& file) {
  mujoco_model mj(file);
  mjModel* m = mj.m;
  mjData* d = mj.d;
  const double inertia_difference = match_inertias(scene, m, d);
  WARN(file << ": MuJoCo's inertias differ from flange's by " << inertia_difference
            << " relative at most (MuJoCo's eigen-solver)");
  REQUIRE(m->nv == S::n_v);
  REQUIRE(m->nq == S::n_q);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst_free = 0, worst_forced = 0, worst_mass = 0;
  for (int k = 0; k < 100; ++k) {
    random_state(m, d, rng);
    const auto x = from_mujoco<S>(m, d);
    // The rates in flange's order for each of MuJoCo's dofs.
    std::vector<int> to_flange(m->nv);
    for (int j = 0; j < m->njnt; ++j) {
      const int n = m->jnt_type[j] == mjJNT_FREE ? 6 : 1;
      for (int i = 0; i < n; ++i)
        to_flange[m->jnt_dofadr[j] + i] = S::v_offset(mj_id2name(m, mjOBJ_JOINT, j)) + i;
    }
    auto check = [&](const std::vector<double>& tau, double& worst) {
      for (int i = 0; i < m->nv; ++i) d->qfrc_applied[i] = tau[i];
      mj_forward(m, d);
      // flange: q̈ = M⁻¹·(τ − b), τ added to v̇(τ = 0) through flange's own M.
      typename S::state_type dx;
      scene(x, dx, 0.0);
      const auto M = flange::mass_matrix(scene, x.data());
      Eigen::Matrix<double, S::n_v, 1> t = Eigen::Matrix<double, S::n_v, 1>::Zero();
      for (int i = 0; i < m->nv; ++i) t[to_flange[i]] = tau[i];
      const Eigen::Matrix<double, S::n_v, 1> extra = M.ldlt().solve(t);
      std::vector<double> flange_qacc(m->nv);
      for (int i = 0; i < m->nv; ++i) flange_qacc[i] = dx[S::n_q + to_flange[i]] + extra[to_flange[i]];
      worst = std::max(worst, relative_difference(flange_qacc, d->qacc, m->nv));
    };
    check(std::vector<double>(m->nv, 0.0), worst_free);
    std::vector<double> tau(m->nv);
    for (auto& t : tau) t = 10 * u(rng);
    check(tau, worst_forced);
    // The mass matrices, entry by entry.
    std::vector<double> full(m->nv * m->nv);
    mj_fullM(m, full.data(), d->qM);
    const auto M = flange::mass_matrix(scene, x.data());
    double diff = 0, scale = 0;
    for (int i = 0; i < m->nv; ++i)
      for (int j = 0; j < m->nv; ++j) {
        diff = std::max(diff, std::abs(M(to_flange[i], to_flange[j]) - full[i * m->nv + j]));
        scale = std::max(scale, std::abs(full[i * m->nv + j]));
      }
    worst_mass = std::max(worst_mass, diff / scale);
  }
  INFO(file << ": largest relative difference in q̈, τ = 0: " << worst_free << "; random τ: " << worst_forced
            << "; M: " << worst_mass);
  WARN(file << ": largest relative difference in q̈, τ = 0: " << worst_free << "; random τ: " << worst_forced
            << "; M: " << worst_mass);
  CHECK(worst_free <= 1e-9);
  CHECK(worst_forced <= 1e-9);
  CHECK(worst_mass <= 1e-12);  // both sums of the same products: round-off
}

}  // namespace

TEST_CASE("a 2-link planar arm from URDF: flange and MuJoCo give the same accelerations") {
  const auto arm = two_link_planar::make_scene();
  static_assert(two_link_planar::scene_type::n_equations == two_link_planar::scene_type::n_unknowns);
  check_against_mujoco(arm, FLANGE_URDF_DIR "/two_link_planar.urdf");
}

TEST_CASE("a 6-joint arm with turned origins, skew axes and a fixed tool: flange and MuJoCo agree") {
  const auto arm = arm6::make_scene();
  check_against_mujoco(arm, FLANGE_URDF_DIR "/arm6.urdf");
}

TEST_CASE("centres of mass at the link origins, principal moments out of order: flange and MuJoCo agree") {
  const auto arm = com_at_origin::make_scene();
  check_against_mujoco(arm, FLANGE_URDF_DIR "/com_at_origin.urdf");
}

TEST_CASE("a floating base with two legs from URDF: flange and MuJoCo agree") {
  const auto robot = floating_legs::make_scene();
  check_against_mujoco(robot, FLANGE_URDF_DIR "/floating_legs.urdf");
}

TEST_CASE("a floating base's state is its world pose, as MuJoCo's qpos: the centre of mass agrees, and --floating-base "
          "gives the same robot") {
  // The floating joint's <origin> is turned and raised (floating_legs.urdf):
  // MuJoCo's qpos is the trunk's world pose, and so is flange's state.
  const auto robot = floating_legs::make_scene();
  using S = decltype(robot);
  mujoco_model mj(FLANGE_URDF_DIR "/floating_legs.urdf");
  mjModel* m = mj.m;
  mjData* d = mj.d;
  // The URDF's home pose: MuJoCo's qpos0, flange's home_state.
  for (int i = 0; i < m->nq; ++i) d->qpos[i] = m->qpos0[i];
  for (int i = 0; i < m->nv; ++i) d->qvel[i] = 0;
  const auto home = from_mujoco<S>(m, d);
  const auto mine = floating_legs::home_state(robot);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(home[i] - mine[i]) < 1e-15);
  double dot = 0;
  for (int i = 3; i < 7; ++i) dot += home[i] * mine[i];
  CHECK(std::abs(std::abs(dot) - 1) < 1e-15);  // one orientation (q and −q are one)
  CHECK(mine[2] == 0.6);
  // The centre of mass at random states: MuJoCo's subtree_com of the world
  // body against flange's bodies at their recovered frames.
  const auto bs = bodies(robot);
  double total = 0;
  for (const auto& b : bs) total += b.m;
  const auto free_root = legs_fixed_root::make_scene();
  using F = decltype(free_root);
  static_assert(F::n_q == S::n_q && F::n_v == S::n_v);
  static_assert(F::q_offset<"floating_base">() == S::q_offset<"base">());
  std::mt19937 rng(11);
  double worst_com = 0, worst_twin = 0;
  for (int k = 0; k < 50; ++k) {
    random_state(m, d, rng);
    mj_forward(m, d);
    const auto x = from_mujoco<S>(m, d);
    const auto sol = recover(robot, 0.0, x);
    flange::Vec3d com = flange::Vec3d::Zero();
    for (const auto& b : bs) {
      const auto& f = sol.frame(std::string(b.name) + ".frame_a");
      com += b.m * (f.r + f.R.transpose() * b.r_cm);
    }
    com /= total;
    worst_com = std::max(worst_com, (com - flange::Vec3d(d->subtree_com[0], d->subtree_com[1], d->subtree_com[2])).norm());
    // The twin written without a floating joint, imported with --floating-base.
    typename S::state_type dx, dy;
    robot(x, dx, 0.0);
    free_root(x, dy, 0.0);
    for (int i = 0; i < S::n_state; ++i) worst_twin = std::max(worst_twin, std::abs(dx[i] - dy[i]) / (1 + std::abs(dx[i])));
  }
  WARN("centre of mass, flange against MuJoCo: " << worst_com << " m; the --floating-base twin: " << worst_twin);
  CHECK(worst_com < 1e-14);
  CHECK(worst_twin < 1e-13);
}
