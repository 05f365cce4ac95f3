// The analytic Jacobian (dynamics/derivatives.hpp) against the dual-number
// Jacobian of the same scene (jacobian_dual: forward mode through the whole
// derivative, sharing none of the derivatives' arithmetic) and central
// differences, over a list of scene shapes, with the stack poisoned before
// each call so that a value read before it is written shows as a wrong
// answer. (linearize_test.cpp holds the cart-pole's, analytic too, to its
// closed form.)
#include <catch2/catch.hpp>

#include <flange/models/chain.hpp>
#include <flange/models/tree.hpp>
#include <flange/simulate/jacobian.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
/// Both Jacobians and ∂f/∂t at three random states. The two differ by the
/// round-off of their solves, a few ε times the largest entry over M's
/// condition: 1e-12 of the largest entry is the bar (measured: 3e-14 at most).
template <class S>
void agree(const S& scene, std::mt19937& rng, double t = 0.3) {
  static_assert(detail::analytic_derivatives<S>(), "the scene should take the analytic Jacobian");
  for (int k = 0; k < 3; ++k) {
    const auto x = test::random_state(scene, rng);
    Eigen::Matrix<double, S::n_state, 1> ft, ft_dual;
    test::poison_stack();
    const auto J = jacobian(scene, t, x, &ft);
    test::poison_stack();
    const auto J_dual = jacobian_dual(scene, t, x, &ft_dual);
    const double scale = std::max(1.0, J_dual.cwiseAbs().maxCoeff());
    INFO("state " << k << ", largest entry " << scale);
    CHECK((J - J_dual).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    CHECK((ft - ft_dual).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    CHECK(J.allFinite());
    // And central differences to their accuracy (h = ε^(1/3): about 1e-10
    // relative, so 1e-7 of the largest entry; jacobian_test.cpp's bar).
    Eigen::Matrix<double, S::n_state, 1> ft_fd;
    const auto J_fd = jacobian_finite_difference(scene, t, x, &ft_fd);
    CHECK((J - J_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
    CHECK((ft - ft_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  }
}

/// A random tree of one-axis joints (Revolute, Prismatic: typed and run-time
/// axes, axis laws, offsets, joints connected either way round, every body
/// kind) without force elements.
template <unsigned Seed, int N, bool Planar>
constexpr models::tree_shape one_axis_tree() {
  auto t = models::random_tree_shape(Seed, N, Planar);
  for (int i = 0; i < t.n; ++i) {
    t.torque[i] = false;
    t.line[i] = -2;
    t.load[i] = 0;
  }
  return t;
}
}  // namespace

TEST_CASE("the analytic Jacobian equals the dual-number Jacobian on chains") {
  std::mt19937 rng(48);
  auto p7 = models::random_chain_params<7>(rng);
  agree(models::chain<7, models::runtime_axes>(p7), rng);
  auto p5 = models::random_chain_params<5>(rng);
  agree(models::chain<5, models::planar_axes>(p5), rng);
  auto p4 = models::random_chain_params<4>(rng);
  p4.stiffness = 3;
  p4.damping = 0.4;
  agree(models::chain<4, models::runtime_axes, axis_law::spring_damper>(p4), rng);
  auto p3 = models::random_chain_params<3>(rng);
  agree(models::chain<3, models::runtime_axes, axis_law::none, gravity_kind::none, inertia_kind::point>(p3), rng);
  auto p2 = models::random_chain_params<2>(rng);
  agree(models::chain<2, models::runtime_axes>(p2), rng);
  auto p1 = models::random_chain_params<1>(rng);
  agree(models::chain<1, models::runtime_axes>(p1), rng);
}

TEST_CASE("the analytic Jacobian equals the dual-number Jacobian on random trees") {
  std::mt19937 rng(4848);
  auto check = [&]<unsigned Seed, int N, bool Planar>() {
    constexpr auto shape = one_axis_tree<Seed, N, Planar>();
    INFO("tree seed " << Seed << ", " << N << " joints" << (Planar ? ", planar" : ""));
    agree(models::tree<shape>(test::tree_params<shape.n>(rng)), rng);
  };
  check.operator()<5, 8, false>();
  check.operator()<9, 8, true>();
  check.operator()<17, 12, false>();
  check.operator()<23, 6, false>();
}

TEST_CASE("a drive of time is differentiated in t, a drive of the state takes dual numbers") {
  std::mt19937 rng(7);
  auto tau = [](auto t) {
    using std::sin;
    return 0.7 * sin(3.0 * t);
  };
  const auto arm = scene(World<"world">{}, revolute<"j0">(tau, Vec3d(0, 0.6, 0.8)), FixedTranslation<"r0">({.d = Vec3d(0.5, 0, 0.1)}),
                         Body<"b0">({.m = 1.3, .J = Vec3d(0.02, 0.03, 0.04).asDiagonal()}),
                         Revolute<"j1", axis::x>{}, FixedTranslation<"r1">({.d = Vec3d(0.4, 0.1, 0)}),
                         Body<"b1">({.m = 0.8, .J = Vec3d(0.01, 0.02, 0.03).asDiagonal()}),
                         connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "r0.frame_a">,
                         connect<"r0.frame_b", "b0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
                         connect<"j1.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">);
  agree(arm, rng, 0.9);
  auto pd = [](auto t, const auto& x) { return -4.0 * q<"j0">(x) - 0.5 * v<"j0">(x) + 0 * t; };
  using PD = Revolute<"j0", axis::any, axis_law::none, decltype(pd)>;
  static_assert(detail::force_reads_state<PD>());
  static_assert(!detail::force_reads_state<Revolute<"j0", axis::any, axis_law::none, decltype(tau)>>());
  static_assert(!detail::force_reads_state<Revolute<"j0">>());
}
