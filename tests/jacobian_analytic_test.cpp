// The analytic Jacobian (dynamics/derivatives.hpp) against the dual-number
// Jacobian of the same scene (jacobian_dual: forward mode through the whole
// derivative, sharing none of the derivatives' arithmetic) and central
// differences, over a list of scene shapes, with the stack poisoned before
// each call so that a value read before it is written shows as a wrong
// answer. (linearize_test.cpp holds the cart-pole's, analytic too, to its
// closed form.)
#include <catch2/catch.hpp>

#include <flange/models/chain.hpp>
#include <flange/models/paper.hpp>
#include <flange/models/tree.hpp>
#include <flange/simulate/jacobian.hpp>

#include "jacobian_agree.hpp"
#include "tree_laws.hpp"

using namespace flange;
using test::agree;

namespace {
/// A PD law on the joint named Name, about its zero.
template <fixed_string Name>
auto pd_of(double kp, double kd) {
  return [kp, kd](auto, const auto& x) { return -kp * q<Name>(x) - kd * v<Name>(x); };
}

/// A random tree of one-axis joints (Revolute, Prismatic: typed and run-time
/// axes, axis laws, offsets, joints connected either way round, every body
/// kind) without force elements.
template <unsigned Seed, int N, bool Planar>
constexpr models::tree_shape one_axis_tree() {
  return test::without_force_elements(models::random_tree_shape(Seed, N, Planar));
}
}  // namespace

TEST_CASE("the analytic Jacobian equals the dual-number Jacobian on chains") {
  // (The chains of seven links and more take the passes' pair loops over
  // stacked columns, the shorter ones their loops up the ancestors.)
  std::mt19937 rng(48);
  auto p7 = models::random_chain_params<7>(rng);
  agree(models::chain<7, models::runtime_axes>(p7), rng);
  auto p8 = models::random_chain_params<8>(rng);
  agree(models::chain<8, models::planar_axes>(p8), rng);
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
  // Up to four nodes every pass is written out node by node in the plane
  // (over_nodes), only the backward ones in space (the chains above).
  auto q2 = models::random_chain_params<2>(rng);
  agree(models::chain<2, models::planar_axes>(q2), rng);
  auto q3 = models::random_chain_params<3>(rng);
  agree(models::chain<3, models::planar_axes>(q3), rng);
  auto q4 = models::random_chain_params<4>(rng);
  agree(models::chain<4, models::planar_axes>(q4), rng);
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
  // Up to four nodes a typed joint at the root has its column's shape in
  // the passes (a turn about a coordinate axis, a translation): here a
  // Revolute about z and one about x, connected the other way round.
  check.operator()<28, 3, false>();
  check.operator()<1, 2, false>();
}

TEST_CASE("force elements: the analytic Jacobian equals the dual-number Jacobian") {
  // Random trees with every force element of models/tree.hpp (torques
  // between links, line forces, loads from the World), spatial and planar,
  // and the paper's robot arm (a Torque from the World).
  std::mt19937 rng(4850);
  auto check = [&]<unsigned Seed, int N, bool Planar>() {
    constexpr auto shape = models::random_tree_shape(Seed, N, Planar);
    INFO("tree seed " << Seed << ", " << N << " joints" << (Planar ? ", planar" : ""));
    agree(models::tree<shape>(test::tree_params<shape.n>(rng)), rng);
  };
  check.operator()<5, 8, false>();
  check.operator()<9, 8, true>();
  check.operator()<31, 6, false>();
  const auto arm = models::robot_arm({}, Vec3d(0.1, -0.2, 0.3));
  agree(arm, rng);
  // jacobian() itself takes dual numbers for a scene of one rate with a
  // force element on its link or in the plane (they are cheaper there), the
  // analytic path for one rate in space without loads and from two rates on.
  STATIC_REQUIRE(!detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(arm)>>());
  STATIC_REQUIRE(!detail::jacobian_takes_analytic<decltype(models::chain<1, models::planar_axes>({}))>());
  STATIC_REQUIRE(detail::jacobian_takes_analytic<decltype(models::chain<1, models::runtime_axes>({}))>());
  STATIC_REQUIRE(detail::jacobian_takes_analytic<decltype(models::chain<2, models::runtime_axes>({}))>());
  agree(models::robot_arm({}, [](auto t) { return Vec3<decltype(t)>(0.0 * t, 0.0 * t, 0.5 * t); }), rng);
  // In space, force elements that read their links' motions and the time
  // alone take dual numbers in those links' motions (local_loads: the random
  // trees above); one that reads the joint state, dual numbers in every
  // direction of the state, as the planar scenes' loads do.
  STATIC_REQUIRE(!detail::local_loads<std::remove_cvref_t<decltype(arm)>>());
  STATIC_REQUIRE(detail::local_loads<decltype(models::tree<models::random_tree_shape(5, 8, false)>(
                     test::tree_params<8>(rng)))>());
  const auto pd = scene(
      World<"world">({.g = {0.3, -9.81, 0.2}}), Revolute<"j1", axis::x>{},
      FixedTranslation<"r1">({.d = {0.3, 0.1, 0}}), Body<"b1">({.m = 1.0, .J = test::random_inertia(rng)}),
      Revolute<"j2", axis::y>{}, FixedTranslation<"r2">({.d = {0.2, 0, 0.1}}),
      Body<"b2">({.m = 0.7, .J = test::random_inertia(rng)}), torque<"motor">([](auto t, const auto& x) {
        using T = decltype(t);
        return Vec3<T>(-2.0 * q<"j1">(x), T(0.1) * t, -0.5 * v<"j2">(x) + 0.3 * q<"j2">(x));
      }),
      connect<"world.frame_b", "j1.frame_a">, connect<"world.frame_b", "motor.frame_a">,
      connect<"j1.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">, connect<"r1.frame_b", "j2.frame_a">,
      connect<"j2.frame_b", "r2.frame_a">, connect<"r2.frame_b", "b2.frame_a">, connect<"r2.frame_b", "motor.frame_b">);
  STATIC_REQUIRE(!detail::local_loads<std::remove_cvref_t<decltype(pd)>>());
  agree(pd, rng);
}

TEST_CASE("a planar scene's Jacobian in the plane's arithmetic equals the dual numbers in 3-D") {
  // Everything the plane drops made non-zero: offsets, centre-of-mass offsets
  // and gravity along the normal, products of inertia; joints either way
  // round, prismatic joints along both in-plane axes, normals z and x.
  std::mt19937 rng(4849);
  for (int k = 0; k < 3; ++k) {
    auto p = test::chain_params<5>(rng);
    p.g = Vec3d(test::uniform(rng, -5, 5), -9.81, test::uniform(rng, -5, 5));
    const auto c = models::chain<5, models::planar_axes>(p);
    STATIC_REQUIRE(std::is_same_v<detail::geometry_t<std::remove_cvref_t<decltype(c)>>, detail::plane<2>>);
    agree(c, rng);
  }
  const Vec3d off(0.3, -0.4, 0.7);
  const auto z = scene(
      World<"world">({.g = {1.0, -9.81, 2.0}}), Prismatic<"rail", axis::x>({.f = 0.4}),
      Body<"cart", cm::offset>({.m = 1.4, .J = test::random_inertia(rng), .r_cm = off}),
      FixedTranslation<"arm">({.d = off}), Revolute<"pivot", axis::z>{},  // reversed: frame_b toward the World
      FixedTranslation<"rope">({.d = {1.0, 0.2, 0.3}}), Body<"load">({.m = 0.9, .J = test::random_inertia(rng)}),
      Prismatic<"slide", axis::y>({.f = -0.3}), Body<"tip">({.m = 0.3, .J = test::random_inertia(rng)}),
      connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
      connect<"rail.frame_b", "arm.frame_a">, connect<"arm.frame_b", "pivot.frame_b">,
      connect<"pivot.frame_a", "rope.frame_a">, connect<"rope.frame_b", "load.frame_a">,
      connect<"rope.frame_b", "slide.frame_a">, connect<"slide.frame_b", "tip.frame_a">);
  STATIC_REQUIRE(std::is_same_v<detail::geometry_t<std::remove_cvref_t<decltype(z)>>, detail::plane<2>>);
  agree(z, rng);
  const auto x = scene(
      World<"world">({.g = {-3.0, -9.81, 1.0}}), Revolute<"shoulder", axis::x>{},
      FixedTranslation<"upper">({.d = {0.4, 0.5, -0.2}}),
      Body<"b1", cm::offset>({.m = 1.1, .J = test::random_inertia(rng), .r_cm = Vec3d(0.3, 0.1, 0.2)}),
      Prismatic<"reach", axis::z>{}, Body<"b2">({.m = 0.6, .J = test::random_inertia(rng)}),
      Revolute<"wrist", axis::x>{}, FixedTranslation<"hand">({.d = {-0.2, 0.0, 0.3}}),
      Body<"b3">({.m = 0.4, .J = test::random_inertia(rng)}), connect<"world.frame_b", "shoulder.frame_a">,
      connect<"shoulder.frame_b", "upper.frame_a">, connect<"upper.frame_b", "b1.frame_a">,
      connect<"upper.frame_b", "reach.frame_a">, connect<"reach.frame_b", "b2.frame_a">,
      connect<"b2.frame_a", "wrist.frame_b">,  // reversed
      connect<"wrist.frame_a", "hand.frame_a">, connect<"hand.frame_b", "b3.frame_a">);
  STATIC_REQUIRE(std::is_same_v<detail::geometry_t<std::remove_cvref_t<decltype(x)>>, detail::plane<0>>);
  agree(x, rng);
}

TEST_CASE("drives of time and of the state are differentiated: in t, and in every direction of the state") {
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
  // A PD law on j1 that also reads j0 and the time, and j0's drive of time.
  auto coupled = [](auto t, const auto& x) {
    using std::cos;
    return -6.0 * (q<"j1">(x) - 0.3 * q<"j0">(x)) - 0.8 * v<"j1">(x) + 0.2 * v<"j0">(x) * cos(t);
  };
  const auto driven = scene(World<"world">{}, revolute<"j0">(tau, Vec3d(0, 0.6, 0.8)),
                            FixedTranslation<"r0">({.d = Vec3d(0.5, 0, 0.1)}),
                            Body<"b0">({.m = 1.3, .J = Vec3d(0.02, 0.03, 0.04).asDiagonal()}),
                            revolute<"j1", axis::x>(coupled), FixedTranslation<"r1">({.d = Vec3d(0.4, 0.1, 0)}),
                            Body<"b1">({.m = 0.8, .J = Vec3d(0.01, 0.02, 0.03).asDiagonal()}),
                            connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "r0.frame_a">,
                            connect<"r0.frame_b", "b0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
                            connect<"j1.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">);
  agree(driven, rng, 0.9);
  // The paper-style spatial arm of the tutorial: a PD law on every joint.
  agree(scene(World<"world">({.g = {0, 0, -9.81}}), revolute<"shoulder", axis::z>(pd_of<"shoulder">(60, 12)),
              revolute<"elbow", axis::y>(pd_of<"elbow">(150, 20)), revolute<"wrist", axis::y>(pd_of<"wrist">(20, 2)),
              FixedTranslation<"upper">({.d = Vec3d(0.5, 0, 0)}), Body<"b1">({.m = 2.0, .J = Vec3d(0.01, 0.05, 0.05).asDiagonal()}),
              FixedTranslation<"fore">({.d = Vec3d(0.4, 0, 0)}), Body<"b2">({.m = 0.8, .J = Vec3d(0.005, 0.02, 0.02).asDiagonal()}),
              Body<"b3">({.m = 0.2, .J = Vec3d(0.001, 0.002, 0.002).asDiagonal()}),
              connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
              connect<"upper.frame_b", "b1.frame_a">, connect<"upper.frame_b", "elbow.frame_a">,
              connect<"elbow.frame_b", "fore.frame_a">, connect<"fore.frame_b", "b2.frame_a">,
              connect<"fore.frame_b", "wrist.frame_a">, connect<"wrist.frame_b", "b3.frame_a">),
        rng);
  using PD = Revolute<"j0", axis::any, axis_law::none, decltype(pd)>;
  static_assert(detail::force_reads_state<PD>());
  static_assert(!detail::force_reads_state<Revolute<"j0", axis::any, axis_law::none, decltype(tau)>>());
  static_assert(!detail::force_reads_state<Revolute<"j0">>());
}

TEST_CASE("a singular mass matrix stops the analytic Jacobian with the derivative's reason") {
  // j1 turns a point mass about an axis through it: it moves nothing with
  // inertia, and M's pivot for it is zero.
  const auto s = scene(World<"world">{}, Revolute<"j0", axis::z>{}, FixedTranslation<"r0">({.d = Vec3d(0.5, 0, 0)}),
                       Body<"b0">({.m = 1.0, .J = Vec3d(0.1, 0.1, 0.1).asDiagonal()}), Revolute<"j1", axis::z>{},
                       Body<"b1">({.m = 1.0, .J = Mat3d::Zero()}), connect<"world.frame_b", "j0.frame_a">,
                       connect<"j0.frame_b", "r0.frame_a">, connect<"r0.frame_b", "b0.frame_a">,
                       connect<"r0.frame_b", "j1.frame_a">, connect<"j1.frame_b", "b1.frame_a">);
  using S = std::remove_cvref_t<decltype(s)>;
  STATIC_REQUIRE(detail::analytic_derivatives<S>());
  const std::array<double, 4> x{0.3, -0.2, 0.5, 1.0};
  std::array<double, 4> f;
  REQUIRE_THROWS_WITH(s(x, f, 0.0), Catch::Contains("singular mass matrix") && Catch::Contains("\"j1\""));
  REQUIRE_THROWS_WITH(jacobian(s, 0.0, x), Catch::Contains("singular mass matrix") && Catch::Contains("\"j1\""));
  // A state that is not finite is named as such.
  const std::array<double, 4> bad{0.3, std::nan(""), 0.5, 1.0};
  REQUIRE_THROWS_WITH(jacobian(s, 0.0, bad), Catch::Contains("not finite"));
}

TEST_CASE("a singular mass matrix stops a tree's written-out factor with the derivative's reason") {
  // Two branches off b0: j2 turns a body with inertia, j1 a point mass
  // about an axis through it (its pivot is zero). A tree, not a chain, of
  // few nodes: M is factored written out (factor_tree_written_out).
  const auto s = scene(World<"world">{}, Revolute<"j0", axis::z>{}, FixedTranslation<"r0">({.d = Vec3d(0.5, 0, 0)}),
                       Body<"b0">({.m = 1.0, .J = Vec3d(0.1, 0.1, 0.1).asDiagonal()}), Revolute<"j1", axis::z>{},
                       Body<"b1">({.m = 1.0, .J = Mat3d::Zero()}), Revolute<"j2", axis::x>{},
                       FixedTranslation<"r2">({.d = Vec3d(0, 0.4, 0)}),
                       Body<"b2">({.m = 2.0, .J = Vec3d(0.2, 0.1, 0.3).asDiagonal()}),
                       connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "r0.frame_a">,
                       connect<"r0.frame_b", "b0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
                       connect<"j1.frame_b", "b1.frame_a">, connect<"r0.frame_b", "j2.frame_a">,
                       connect<"j2.frame_b", "r2.frame_a">, connect<"r2.frame_b", "b2.frame_a">);
  using S = std::remove_cvref_t<decltype(s)>;
  STATIC_REQUIRE(detail::analytic_derivatives<S>());
  STATIC_REQUIRE(!detail::derivative_nodes<S>::chain);
  STATIC_REQUIRE(detail::unrolled_factor<S>());
  const std::array<double, 6> x{0.3, -0.2, 0.7, 0.5, 1.0, -0.4};
  std::array<double, 6> f;
  REQUIRE_THROWS_WITH(s(x, f, 0.0), Catch::Contains("singular mass matrix") && Catch::Contains("\"j1\""));
  REQUIRE_THROWS_WITH(jacobian(s, 0.0, x), Catch::Contains("singular mass matrix") && Catch::Contains("\"j1\""));
}
