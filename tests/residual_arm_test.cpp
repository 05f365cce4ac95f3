// The robot arm's residual on a consistent assignment of all 106 unknowns,
// built by hand from the paper's reduced relations (its second table), not by
// the library's recovery. Then each variable perturbed alone must disturb
// exactly the equations that the paper's listing says contain it.
#include <map>
#include <set>
#include <vector>

#include <catch2/catch.hpp>
#include <flange/equations/residual.hpp>
#include <flange/models/paper.hpp>

using namespace flange;
using Arm = decltype(models::robot_arm());
using Y = dae_vector<Arm, double>;

namespace {

const models::robot_arm_params P{.m = 1.7, .d = 0.8, .Jx = 0.03, .Jz = 0.05, .g = 9.81};
const double Mz = 2.3;

int frame(int paper_number) { return Arm::topology.by_number[paper_number - 1]; }
auto seg(Y& y, int f, int which) { return y.segment<3>(Arm::frame_offset(f, which)); }
Eigen::Map<Mat3d> mat(Y& y, int f) { return Eigen::Map<Mat3d>(y.data() + Arm::frame_offset(f, 1)); }

struct assignment {
  Y y = Y::Zero(), yd = Y::Zero();
};

/// The paper's second table at joint angle φ, rate φ̇; φ̈ from the paper's
/// final equation (J_z + m d²)·φ̈ + m·d·g·cos φ = M_z.
assignment paper_assignment(double phi, double phid) {
  const double m = P.m, d = P.d, g = P.g;
  const double phidd = (Mz - m * d * g * std::cos(phi)) / (P.Jz + m * d * d);
  const double c = std::cos(phi), s = std::sin(phi);
  Mat3d Rrel;
  Rrel << c, s, 0, -s, c, 0, 0, 0, 1;
  const Vec3d dvec(d, 0, 0), gvec(0, -g, 0), M(0, 0, Mz), n(0, 0, 1);
  const Mat3d J = Vec3d(P.Jx, P.Jz, P.Jz).asDiagonal();
  const Vec3d r8 = Rrel.transpose() * dvec;                                        // (13), (33)
  const Vec3d v = d * Vec3d(-s * phid, c * phid, 0);                               // (17)
  const Vec3d vdot = d * Vec3d(-c * phid * phid - s * phidd, -s * phid * phid + c * phidd, 0);  // R̈_rel'·d
  const Vec3d w = phid * n, wd = phidd * n;
  const Vec3d F8 = m * Rrel * (vdot - gvec);  // (19)
  const Vec3d M8 = J * wd + w.cross(J * w);    // (20)
  const Vec3d M5 = M8 + m * dvec.cross(Rrel * (vdot - gvec));  // (16)

  assignment a;
  auto& y = a.y;
  for (int k = 1; k <= 8; ++k) mat(y, frame(k)) = k <= 3 ? Mat3d::Identity() : Rrel;  // (2),(23),(24),(9),(29),(30),(14),(34)
  seg(y, frame(7), 0) = r8;
  seg(y, frame(8), 0) = r8;  // r1..r6 = 0
  seg(y, frame(8), 2) = F8;
  seg(y, frame(7), 2) = -F8;                      // (35)
  seg(y, frame(6), 2).setZero();                  // (4)
  seg(y, frame(5), 2) = F8;                       // (15)
  seg(y, frame(4), 2) = -F8;                      // (31)
  seg(y, frame(3), 2).setZero();                  // (3)
  seg(y, frame(2), 2) = m * (vdot - gvec);        // (10)
  seg(y, frame(1), 2) = -m * (vdot - gvec);       // (25)
  seg(y, frame(3), 3) = M;                        // (5)
  seg(y, frame(6), 3) = -Rrel * M;                // (6)
  seg(y, frame(8), 3) = M8;
  seg(y, frame(7), 3) = -M8;                      // (36)
  seg(y, frame(5), 3) = M5;
  seg(y, frame(2), 3) = Rrel.transpose() * M5 - M;  // (11)
  seg(y, frame(4), 3) = -M5 + Rrel * M;             // (32)
  seg(y, frame(1), 3) = -Rrel.transpose() * M5;     // (26)
  // Internals: φ and R_rel of the joint, v and ω of the body.
  constexpr int joint = Arm::index_of("joint"), mass = Arm::index_of("mass");
  y(Arm::slot_offset<joint>(8)) = phi;
  Eigen::Map<Mat3d>(y.data() + Arm::slot_offset<joint>(9)) = Rrel;
  y.segment<3>(Arm::slot_offset<mass>(4)) = v;
  y.segment<3>(Arm::slot_offset<mass>(5)) = w;
  // The derivatives the equations use: ṙ8, Ṙ8 = −ω̃·R8, v̇, ω̇.
  auto& yd = a.yd;
  yd.segment<3>(Arm::frame_offset(frame(8), 0)) = v;
  Eigen::Map<Mat3d>(yd.data() + Arm::frame_offset(frame(8), 1)) = -tilde<double>(w) * Rrel;
  yd.segment<3>(Arm::slot_offset<mass>(4)) = vdot;
  yd.segment<3>(Arm::slot_offset<mass>(5)) = wd;
  yd(Arm::slot_offset<joint>(8)) = phid;
  return a;
}

// Rows of the paper's equations (1)-(36): every one is a 3-vector but (12).
int first_row(int eq) { return 3 * (eq - 1) - (eq > 12 ? 2 : 0); }
int rows(int eq) { return eq == 12 ? 1 : 3; }
std::set<int> disturbed(const Eigen::VectorXd& r, double tol) {
  std::set<int> out;
  for (int eq = 1; eq <= 36; ++eq)
    for (int i = 0; i < rows(eq); ++i)
      if (std::abs(r(first_row(eq) + i)) > tol) out.insert(eq);
  return out;
}

}  // namespace

TEST_CASE("the paper's reduced relations solve the robot arm's residual, at rest and in motion") {
  const auto arm = models::robot_arm(P, Vec3d(0, 0, Mz));
  for (auto [phi, phid] : {std::pair{0.0, 0.0}, std::pair{-M_PI / 2, 0.0}, std::pair{0.7, 1.3}, std::pair{-2.9, -4.0}}) {
    const auto a = paper_assignment(phi, phid);
    const auto r = residual(arm, 0.0, a.y, a.yd);
    INFO("φ = " << phi << ", φ̇ = " << phid);
    // Round-off of O(10)-sized products: a few ulps of 100.
    CHECK(r.cwiseAbs().maxCoeff() < 1e-13);
  }
}

TEST_CASE("perturbing one variable disturbs exactly the paper's equations that contain it") {
  const auto arm = models::robot_arm(P, Vec3d(0, 0, Mz));
  const auto base = paper_assignment(0.7, 1.3);
  constexpr int joint = Arm::index_of("joint"), mass = Arm::index_of("mass");
  // variable → the equations of the paper's listing it appears in (read off
  // seed-paper.md, equations (1)-(36), with frames 1..8 as in Figure 2).
  struct perturbation {
    const char* name;
    int offset;  // in y
    bool rotation;
    std::set<int> equations;
  };
  auto fo = [](int k, int which) { return Arm::frame_offset(frame(k), which); };
  const std::vector<perturbation> cases{
      {"r1", fo(1, 0), false, {1, 21, 22}},       {"R1", fo(1, 1), true, {2, 23, 24}},
      {"F1", fo(1, 2), false, {25}},              {"M1", fo(1, 3), false, {26}},
      {"r2", fo(2, 0), false, {8, 21}},           {"R2", fo(2, 1), true, {9, 23}},
      {"F2", fo(2, 2), false, {10, 25}},          {"M2", fo(2, 3), false, {11, 26}},
      {"r3", fo(3, 0), false, {22}},              {"R3", fo(3, 1), true, {6, 24}},
      {"F3", fo(3, 2), false, {3, 25}},           {"M3", fo(3, 3), false, {5, 26}},
      {"r4", fo(4, 0), false, {8, 27, 28}},       {"R4", fo(4, 1), true, {9, 29, 30}},
      {"F4", fo(4, 2), false, {10, 31}},          {"M4", fo(4, 3), false, {11, 12, 32}},
      {"r5", fo(5, 0), false, {13, 27}},          {"R5", fo(5, 1), true, {13, 14, 29}},
      {"F5", fo(5, 2), false, {15, 16, 31}},      {"M5", fo(5, 3), false, {16, 32}},
      {"r6", fo(6, 0), false, {28}},              {"R6", fo(6, 1), true, {6, 30}},
      {"F6", fo(6, 2), false, {4, 31}},           {"M6", fo(6, 3), false, {6, 32}},
      {"r7", fo(7, 0), false, {13, 33}},          {"R7", fo(7, 1), true, {14, 34}},
      {"F7", fo(7, 2), false, {15, 35}},          {"M7", fo(7, 3), false, {16, 36}},
      {"r8", fo(8, 0), false, {33}},              {"R8", fo(8, 1), true, {18, 19, 34}},
      {"F8", fo(8, 2), false, {19, 35}},          {"M8", fo(8, 3), false, {20, 36}},
      {"φ", Arm::slot_offset<joint>(8), false, {7}},
      // R_rel also appears in (11) M4 = −R_rel·M2, but multiplied by M2, which
      // the planar arm keeps at 0 (M2 = R_rel'·M5 − M and M5 = M_z·n), so
      // perturbing R_rel cannot disturb (11).
      {"R_rel", Arm::slot_offset<joint>(9), true, {7, 9, 10}},
      {"v", Arm::slot_offset<mass>(4), false, {17}},
      {"ω", Arm::slot_offset<mass>(5), false, {18, 20}},
  };
  for (const auto& c : cases) {
    for (int k = 0; k < (c.rotation ? 3 : (c.offset == Arm::slot_offset<joint>(8) ? 1 : 3)); ++k) {
      auto y = base.y;
      const double delta = 1e-3;
      if (c.rotation) {
        Eigen::Map<Mat3d> R(y.data() + c.offset);
        R = Mat3d(axis_rotation<double>(Vec3d::Unit(k), delta) * R);
      } else {
        y(c.offset + k) += delta;
      }
      const Eigen::VectorXd r = residual(arm, 0.0, y, base.yd);
      INFO(c.name << " component " << k);
      // Disturbed equations move by O(δ) = 1e-3 times O(1) coefficients;
      // untouched ones stay at round-off.
      std::set<int> got = disturbed(r, 1e-9);
      // A perturbation along a direction an equation ignores (e.g. r along n
      // in (12)) leaves it quiet; so every disturbed equation must be listed,
      // and over the three directions every listed one must be disturbed.
      for (int eq : got) CHECK(c.equations.count(eq) == 1);
      static std::map<std::string, std::set<int>> seen;
      seen[c.name].insert(got.begin(), got.end());
      if (k == (c.rotation || c.offset != Arm::slot_offset<joint>(8) ? 2 : 0)) CHECK(seen[c.name] == c.equations);
    }
  }
}
