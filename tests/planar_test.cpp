// Planar scenes in planar arithmetic (planar_algebra, flange/dynamics/algebra.hpp) against the
// spatial Newton–Euler algorithm on the same scene: the same q̈ to round-off,
// with everything a planar algorithm must ignore made non-zero (out-of-plane
// offsets, products of inertia, centre-of-mass offsets, gravity along the
// normal, torque components off the normal), joints either way round, and
// prismatic joints along both in-plane axes.
#include <catch2/catch.hpp>
#include <flange/dynamics/forward_dynamics.hpp>
#include <flange/equations_of_motion.hpp>

#include "random_params.hpp"

using namespace flange;

namespace {
/// The largest |q̈_planar − q̈_spatial| relative to the size of q̈ and of the
/// generalised forces (the terms that cancel into it).
template <class S>
double disagreement(const S& s, std::mt19937& rng, double t = 0.3) {
  constexpr int N = S::n_q;
  std::array<double, N> q, qd, a, b;
  for (auto& v : q) v = test::uniform(rng, -3, 3);
  for (auto& v : qd) v = test::uniform(rng, -3, 3);
  accelerations_planar(s, t, q.data(), qd.data(), a.data());
  accelerations_newton_euler(s, t, q.data(), qd.data(), b.data());
  double worst = 0, scale = 1;
  for (int i = 0; i < N; ++i) scale = std::max(scale, std::abs(b[i]));
  for (int i = 0; i < N; ++i) worst = std::max(worst, std::abs(a[i] - b[i]) / scale);
  return worst;
}
// Round-off of either algorithm: a few hundred operations on numbers of
// order one, each off by ε ≈ 1.1e-16, amplified by the mass matrix's
// condition (below 1e3 for these parameters).
constexpr double round_off = 1e-11;
}  // namespace

TEST_CASE("the planar test classifies scenes by their joint axes") {
  STATIC_REQUIRE(detail::planar_axis<decltype(models::robot_arm())>() == 2);
  STATIC_REQUIRE(detail::planar_axis<decltype(models::gantry_crane())>() == 2);
  STATIC_REQUIRE(detail::planar_axis<decltype(models::chain<3, models::planar_axes>({}))>() == 2);
  STATIC_REQUIRE(detail::planar_axis<decltype(models::chain<3, models::runtime_axes>({}))>() == -1);
  // A rail along the normal is not planar.
  using Z = decltype(scene(World<"world">{}, Prismatic<"rail", axis::z>({}), Body<"cart">({.m = 1.0}),
                           Revolute<"pivot", axis::z>{}, Body<"load">({.m = 1.0}),
                           connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
                           connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "load.frame_a">));
  STATIC_REQUIRE(detail::planar_axis<Z>() == -1);
}

TEST_CASE("planar arithmetic gives the spatial algorithm's accelerations on the paper's scenes") {
  std::mt19937 rng(11);
  for (int k = 0; k < 100; ++k) {
    auto pa = test::arm_params(rng);
    const auto arm = models::robot_arm(pa, Vec3d(0.3, -0.2, test::uniform(rng, -2, 2)));
    CHECK(disagreement(arm, rng) < round_off);
    const auto crane = models::gantry_crane(test::crane_params(rng), test::uniform(rng, -3, 3));
    CHECK(disagreement(crane, rng) < round_off);
  }
}

TEST_CASE("planar arithmetic ignores exactly what cannot change q̈ in a planar chain") {
  std::mt19937 rng(12);
  for (int k = 0; k < 50; ++k) {
    auto p = test::chain_params<5>(rng);  // full inertias, offsets out of the plane
    p.g = Vec3d(test::uniform(rng, -5, 5), -9.81, test::uniform(rng, -5, 5));
    const auto c = models::chain<5, models::planar_axes>(p);
    CHECK(disagreement(c, rng) < round_off);
    // Without gravity the planar code skips every zero acceleration and every
    // rotation nothing uses (planar_flags); the spatial code does not.
    const auto free = models::chain<5, models::planar_axes, axis_law::spring_damper, gravity_kind::none>(p);
    CHECK(disagreement(free, rng) < round_off);
  }
}

TEST_CASE("planar arithmetic ignores exactly what cannot change q̈ in a branched planar tree") {
  // Random planar trees (models/tree.hpp): branches, prismatic joints along x
  // and y, joints either way round, every force element, offsets and forces
  // out of the plane.
  std::mt19937 rng(15);
  constexpr auto a = models::random_tree_shape(21, 7, true);
  constexpr auto b = models::random_tree_shape(22, 6, true);
  for (int k = 0; k < 20; ++k) {
    CHECK(disagreement(models::tree<a>(test::tree_params<a.n>(rng)), rng) < round_off);
    CHECK(disagreement(models::tree<b>(test::tree_params<b.n>(rng)), rng) < round_off);
  }
}

TEST_CASE("planar arithmetic on mixed, reversed and offset joints") {
  std::mt19937 rng(13);
  for (int k = 0; k < 50; ++k) {
    const Vec3d off(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1));
    const auto s = scene(
        World<"world">({.g = {1.0, -9.81, 2.0}}), Prismatic<"rail", axis::x>({.f = 0.4}),
        Body<"cart", cm::offset>({.m = test::uniform(rng, 0.5, 2), .J = test::random_inertia(rng), .r_cm = off}),
        FixedTranslation<"arm">({.d = off}), Revolute<"pivot", axis::z>{},  // reversed: frame_b toward the World
        FixedTranslation<"rope">({.d = {1.0, 0.2, 0.3}}),
        Body<"load">({.m = test::uniform(rng, 0.5, 2), .J = test::random_inertia(rng)}),
        Prismatic<"slide", axis::y>({.f = -0.3}), Body<"tip">({.m = 0.3, .J = test::random_inertia(rng)}),
        Torque<"motor">({.M_ext = Vec3d(0.5, 0.1, 0.8)}),
        connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
        connect<"rail.frame_b", "arm.frame_a">, connect<"arm.frame_b", "pivot.frame_b">,
        connect<"pivot.frame_a", "rope.frame_a">, connect<"rope.frame_b", "load.frame_a">,
        connect<"rope.frame_b", "slide.frame_a">, connect<"slide.frame_b", "tip.frame_a">,
        connect<"arm.frame_b", "motor.frame_a">, connect<"pivot.frame_a", "motor.frame_b">);
    STATIC_REQUIRE(detail::planar_axis<std::remove_cvref_t<decltype(s)>>() == 2);
    CHECK(disagreement(s, rng) < round_off);
  }
}
