// The folded mass matrix (dynamics/model.hpp, folded_mass_matrix): a scene
// whose joints all hang from the World, each with a subspace fixed in its
// link, has an M that does not depend on q, folded into M⁻¹ at construction;
// a FreeMotion's block is M₀ turned by its rotation, Tᵀ·M₀·T, and folds as
// M₀. Checked here: which scenes qualify; that M(q) really is the same at
// every q, or M₀ turned (the premise, by the mass-matrix pass itself); v̇
// against the articulated-body algorithm, which never forms M, and against a
// dense solve of M(q) at the state; the exact Jacobian through the folded
// inverse; and a singular folded M still reported at the evaluation, naming
// its joint.
#include <Eigen/Cholesky>
#include <catch2/catch.hpp>

#include <random>

#include <flange/dynamics/other_algorithm.hpp>
#include <flange/equations_of_motion.hpp>
#include <flange/simulate/jacobian.hpp>

using namespace flange;
using Catch::Matchers::Contains;

namespace {

/// Three joints on the World: a revolute about z carrying an offset body, a
/// prismatic along x, and a revolute on a run-time axis connected the other
/// way round (its frame_b toward the World), with a motor torque.
auto rack(double m_last) {
  const Vec3d n = Vec3d(1, 2, 2).normalized();
  return scene(World<"world">{}, Revolute<"turn", axis::z>{}, FixedTranslation<"arm">({.d = {0.4, 0.1, 0}}),
               Body<"bob", cm::offset>({.m = 1.5, .J = Vec3d(0.02, 0.03, 0.04).asDiagonal(), .r_cm = {0.05, 0, 0.02}}),
               Prismatic<"slide", axis::x>({.f = -0.5}), Body<"cart">({.m = 3.0, .J = Mat3d::Identity()}),
               Revolute<"tilt">({.n = n}), Torque<"motor">({.M_ext = 0.3 * n}),
               Body<"plate", cm::offset>({.m = m_last, .J = m_last * Vec3d(0.1, 0.2, 0.15).asDiagonal(),
                                          .r_cm = {0.1, -0.2, 0.3}}),
               connect<"world.frame_b", "turn.frame_a">, connect<"turn.frame_b", "arm.frame_a">,
               connect<"arm.frame_b", "bob.frame_a">, connect<"world.frame_b", "slide.frame_a">,
               connect<"slide.frame_b", "cart.frame_a">, connect<"world.frame_b", "tilt.frame_b">,
               connect<"world.frame_b", "motor.frame_b">, connect<"tilt.frame_a", "plate.frame_a">,
               connect<"tilt.frame_a", "motor.frame_a">);
}
using Rack = decltype(rack(1.0));

static_assert(detail::folded_mass_matrix<Rack>());
static_assert(detail::folded_mass_matrix<decltype(models::robot_arm())>(), "the paper's arm: one joint on the World");
static_assert(!detail::folded_mass_matrix<decltype(models::gantry_crane())>(), "the rope hangs from the trolley");
static_assert(!detail::folded_mass_matrix<decltype(models::fourbar(models::fourbar_params{}))>(), "a loop");
static_assert(!detail::folded_mass_matrix<decltype(scene(World<"world">{}, Spherical<"ball">{},
                                                           Body<"b">({.m = 1.0, .J = Mat3d::Identity()}),
                                                           connect<"world.frame_b", "ball.frame_a">,
                                                           connect<"ball.frame_b", "b.frame_a">))>(),
              "a Spherical joint does not declare a fixed subspace");

/// Two free bodies and a revolute joint on the World: one body whose centre
/// of mass is off its frame, with a full inertia, and one whose FreeMotion
/// hangs on a turned and shifted frame.
auto fliers() {
  Mat3d J;
  J << 0.05, 0.01, -0.02, 0.01, 0.08, 0.015, -0.02, 0.015, 0.07;
  return scene(World<"world">{}, FreeMotion<"fly">{},
               Body<"lump", cm::offset>({.m = 2.0, .J = J, .r_cm = {0.1, -0.05, 0.2}}),
               FixedRotation<"mount">({.r = {0.3, 0.1, -0.2}, .R = orientation::rpy(0.3, -0.2, 0.5)}),
               FreeMotion<"drift">{}, Body<"puck", cm::offset>({.m = 0.7, .J = 0.5 * J, .r_cm = {-0.1, 0.0, 0.05}}),
               Revolute<"spin", axis::y>{}, Body<"wheel">({.m = 1.0, .J = Mat3d::Identity() * 0.1}),
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "lump.frame_a">,
               connect<"world.frame_b", "mount.frame_a">, connect<"mount.frame_b", "drift.frame_a">,
               connect<"drift.frame_b", "puck.frame_a">, connect<"world.frame_b", "spin.frame_a">,
               connect<"spin.frame_b", "wheel.frame_a">);
}
using Fliers = decltype(fliers());
static_assert(detail::folded_mass_matrix<Fliers>(), "free bodies on the World fold too");

double rel(const auto& a, const auto& b) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num = std::max(num, std::abs(a[i] - b[i]));
    den = std::max(den, std::abs(b[i]));
  }
  return num / std::max(den, 1e-300);
}

}  // namespace

TEST_CASE("a scene whose joints all hang from the World has one M at every q, and v̇ from its folded inverse") {
  const auto s = rack(2.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  const Mat3d M0 = mass_matrix(s, std::array<double, 3>{0, 0, 0}.data());
  double worst_M = 0, worst_aba = 0, worst_dense = 0;
  for (int k = 0; k < 20; ++k) {
    std::array<double, 6> x;
    for (auto& xi : x) xi = u(rng);
    // The premise: the mass-matrix pass at q gives the M folded at q = 0.
    const Mat3d M = mass_matrix(s, x.data());
    worst_M = std::max(worst_M, (M - M0).norm() / M0.norm());
    // v̇ from the folded inverse (the default) against the articulated body.
    std::array<double, 3> a, b;
    accelerations(s, 0.0, x.data(), x.data() + 3, a.data());
    accelerations_other(s, 0.0, x.data(), x.data() + 3, b.data());
    worst_aba = std::max(worst_aba, rel(a, b));
    // And against M(q)·v̇ = τ − b(q, v), solved densely at the state: the
    // inverse dynamics at v̇ = 0 give b less the force elements' loads (the
    // motor), and τ is the slide's own force, −0.5 N on v[1].
    const std::array<double, 3> zero{};
    const auto bias = inverse_dynamics(s, 0.0, x.data(), x.data() + 3, zero.data());
    const Vec3d d = M.ldlt().solve(Vec3d(0, -0.5, 0) - Vec3d(bias[0], bias[1], bias[2]));
    worst_dense = std::max(worst_dense, rel(a, std::array<double, 3>{d(0), d(1), d(2)}));
  }
  INFO("M(q) − M(0): " << worst_M << ", folded − ABA: " << worst_aba << ", folded − dense: " << worst_dense);
  CHECK(worst_M <= 1e-15);
  CHECK(worst_aba <= 1e-13);
  CHECK(worst_dense <= 1e-13);
  CHECK(M0(0, 1) == 0.0);  // block diagonal: no joint moves another
}

TEST_CASE("free bodies: M(q) is M₀ turned by each body's rotation, and v̇ from the folded inverse") {
  const auto s = fliers();
  constexpr int NQ = Fliers::n_q, NV = Fliers::n_v;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  std::array<double, NQ> q0{};
  detail::neutral_configuration(s, q0.data());
  const auto M0 = mass_matrix(s, q0.data());
  double worst_M = 0, worst_aba = 0, worst_dense = 0;
  for (int k = 0; k < 20; ++k) {
    std::array<double, NQ + NV> x;
    for (auto& xi : x) xi = u(rng);
    for (int at : {3, 10}) {  // the quaternions, at unit norm
      double n = 0;
      for (int i = 0; i < 4; ++i) n += x[at + i] * x[at + i];
      for (int i = 0; i < 4; ++i) x[at + i] /= std::sqrt(n);
    }
    // The premise: M(q) = Tᵀ·M₀·T with T = diag(E, 1) on each free body's
    // rates, E its rotation (frame_a into frame_b coordinates).
    const auto M = mass_matrix(s, x.data());
    Eigen::Matrix<double, NV, NV> T = Eigen::Matrix<double, NV, NV>::Identity();
    for (int at : {3, 10}) {
      const Mat3d E = quaternion::to_rotation<double>(x.data() + at);
      const int v0 = at == 3 ? 0 : 6;
      T.block<3, 3>(v0, v0) = E;
    }
    worst_M = std::max(worst_M, (M - T.transpose() * M0 * T).norm() / M0.norm());
    std::array<double, NV> a, b;
    accelerations(s, 0.0, x.data(), x.data() + NQ, a.data());
    accelerations_other(s, 0.0, x.data(), x.data() + NQ, b.data());
    worst_aba = std::max(worst_aba, rel(a, b));
    const std::array<double, NV> zero{};
    const auto bias = inverse_dynamics(s, 0.0, x.data(), x.data() + NQ, zero.data());
    Eigen::Matrix<double, NV, 1> rhs;
    for (int i = 0; i < NV; ++i) rhs(i) = -bias[i];
    const Eigen::Matrix<double, NV, 1> d = M.ldlt().solve(rhs);
    std::array<double, NV> dense;
    for (int i = 0; i < NV; ++i) dense[i] = d(i);
    worst_dense = std::max(worst_dense, rel(a, dense));
  }
  INFO("M(q) − Tᵀ·M₀·T: " << worst_M << ", folded − ABA: " << worst_aba << ", folded − dense: " << worst_dense);
  CHECK(worst_M <= 1e-15);
  CHECK(worst_aba <= 1e-13);
  CHECK(worst_dense <= 1e-13);
  CHECK(M0(0, 6) == 0.0);  // block diagonal: no joint moves another
  CHECK(M0(0, 4) != 0.0);  // the lump's centre of mass is off its frame
}

TEST_CASE("the exact Jacobian of free bodies passes through the folded inverse") {
  const auto s = fliers();
  auto x = initial_state(s);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += 0.1 * std::sin(1.7 * double(i) + 0.3);
  normalize(s, x);
  const auto J = jacobian(s, 0.0, x);
  const auto F = jacobian_finite_difference(s, 0.0, x);
  INFO("‖J − J_fd‖ / ‖J‖ = " << (J - F).norm() / J.norm());
  CHECK((J - F).norm() <= 1e-7 * J.norm());
}

TEST_CASE("the exact Jacobian passes through the folded inverse") {
  const auto s = rack(2.0);
  const std::array<double, 6> x{0.3, -0.2, 1.1, 0.7, -0.4, 2.0};
  const auto J = jacobian(s, 0.0, x);
  const auto F = jacobian_finite_difference(s, 0.0, x);
  INFO("‖J − J_fd‖ / ‖J‖ = " << (J - F).norm() / J.norm());
  CHECK((J - F).norm() <= 1e-7 * J.norm());
}

TEST_CASE("a singular folded M is reported at the evaluation, with its joint, time and state") {
  const auto s = rack(0.0);  // the tilting plate has no mass: its joint moves nothing
  std::array<double, 6> x{0.1, 0.2, 0.3, 0.0, 0.0, 0.0}, dx;
  CHECK_THROWS_AS(s(x, dx, 1.25), simulation_error);
  CHECK_THROWS_WITH(s(x, dx, 1.25), Contains("singular mass matrix") && Contains("t = 1.25") &&
                                        Contains("joint \"tilt\"") && Contains("moves nothing"));
}

TEST_CASE("a long-double derivative solves its own M, not the inverse folded in double") {
  // The folded inverse is a double: a wider scalar forms M and solves it at
  // its own precision (the long-double reference of docs/accuracy-vs-cost.md
  // needs every digit).
  using L = long double;
  const auto s = rack(2.0);
  const std::array<L, 6> x{0.3L, -0.2L, 1.1L, 0.7L, -0.4L, 2.0L};
  std::array<L, 3> a;
  accelerations(s, L(0), x.data(), x.data() + 3, a.data());
  const auto M = mass_matrix(s, x.data());
  const std::array<L, 3> zero{};
  const auto bias = inverse_dynamics(s, L(0), x.data(), x.data() + 3, zero.data());
  const Eigen::Matrix<L, 3, 1> d = M.ldlt().solve(Eigen::Matrix<L, 3, 1>(-bias[0], -0.5L - bias[1], -bias[2]));
  L err = 0;
  for (int i = 0; i < 3; ++i) err = std::max(err, std::abs(a[i] - d(i)) / std::abs(d(i)));
  INFO("long double: folded path − dense solve " << double(err));
  CHECK(err <= 1e-17L);
}
