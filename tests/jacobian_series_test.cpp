// The analytic Jacobian (dynamics/derivatives.hpp) of scenes with joints of
// rates in series (Universal, Cylindrical, Planar: core/joint.hpp,
// sequential_rates), each a row of one-rate nodes: random branched trees of
// every joint kind and every force element of models/tree.hpp, a spatial
// chain of the three with typed and run-time axes, and a planar scene of
// Planar joints in the plane's arithmetic, against the dual-number Jacobian
// of the same scene and central differences (jacobian_agree.hpp).
#include <catch2/catch.hpp>

#include <flange/components/body.hpp>
#include <flange/components/fixed_translation.hpp>
#include <flange/components/world.hpp>
#include <flange/joints/cylindrical.hpp>
#include <flange/joints/planar.hpp>
#include <flange/joints/revolute.hpp>
#include <flange/joints/universal.hpp>
#include <flange/models/tree.hpp>
#include <flange/simulate/jacobian.hpp>

#include "jacobian_agree.hpp"

using namespace flange;

namespace {
/// random_tree_shape with every joint kind, each joint of more than one rate
/// connected frame_a toward the World; with or without force elements.
template <unsigned Seed, int N, bool Loads>
constexpr models::tree_shape series_tree() {
  auto t = models::random_tree_shape(Seed, N, false, true);
  for (int i = 0; i < t.n; ++i)
    if (t.kind[i] != models::joint_kind::revolute) t.reversed[i] = false;
  return Loads ? t : test::without_force_elements(t);
}

/// How many joints of the shape are of kind k.
constexpr int count(const models::tree_shape& t, models::joint_kind k) {
  int n = 0;
  for (int i = 0; i < t.n; ++i) n += t.kind[i] == k;
  return n;
}
}  // namespace

TEST_CASE("random trees with joints of rates in series: the analytic Jacobian equals the dual-number Jacobian") {
  using models::joint_kind;
  std::mt19937 rng(5150);
  auto check = [&]<unsigned Seed, int N, bool Loads>() {
    constexpr auto shape = series_tree<Seed, N, Loads>();
    static_assert(count(shape, joint_kind::universal) + count(shape, joint_kind::cylindrical) +
                      count(shape, joint_kind::planar) >= 2,
                  "each tree should hold joints of rates in series");
    const auto s = models::tree<shape>(test::tree_params<shape.n>(rng));
    STATIC_REQUIRE(detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(s)>>());
    INFO("tree seed " << Seed << ", " << N << " joints: " << count(shape, joint_kind::universal) << " Universal, "
                      << count(shape, joint_kind::cylindrical) << " Cylindrical, "
                      << count(shape, joint_kind::planar) << " Planar" << (Loads ? ", force elements" : ""));
    test::agree(s, rng);
  };
  check.operator()<3, 8, false>();
  check.operator()<11, 8, true>();
}

TEST_CASE("a chain of a Universal, a Cylindrical and a Planar joint, typed and run-time axes") {
  std::mt19937 rng(5151);
  const auto s = scene(World<"world">({.g = {0.3, -9.81, 0.2}}),
                       Universal<"u", axis::x, axis::any>({.n_b = Vec3d(0.2, 1, -0.3).normalized()}),
                       FixedTranslation<"r1">({.d = {0.1, -0.4, 0.05}}),
                       Body<"b1", cm::offset>({.m = 1.3, .J = Vec3d(0.02, 0.03, 0.025).asDiagonal(), .r_cm = {0, -0.2, 0}}),
                       Cylindrical<"c", axis::any>({.n = Vec3d(0.3, -0.2, 1).normalized()}),
                       Body<"b2", cm::offset>({.m = 0.7, .J = Vec3d(0.01, 0.012, 0.008).asDiagonal(), .r_cm = {0.1, 0, 0.2}}),
                       Planar<"p">({.n = Vec3d(0, 0.2, 1).normalized(), .n_x = Vec3d(1, 0.1, 0)}),
                       Body<"b3", cm::offset>({.m = 0.4, .J = Vec3d(0.004, 0.006, 0.005).asDiagonal(), .r_cm = {0.15, -0.05, 0}}),
                       Universal<"u2", axis::z, axis::y>{},
                       Body<"b4", cm::offset>({.m = 0.3, .J = Vec3d(0.003, 0.002, 0.004).asDiagonal(), .r_cm = {0, 0, -0.2}}),
                       connect<"world.frame_b", "u.frame_a">, connect<"u.frame_b", "r1.frame_a">,
                       connect<"u.frame_b", "b1.frame_a">, connect<"r1.frame_b", "c.frame_a">,
                       connect<"c.frame_b", "b2.frame_a">, connect<"c.frame_b", "p.frame_a">,
                       connect<"p.frame_b", "b3.frame_a">, connect<"p.frame_b", "u2.frame_a">,
                       connect<"u2.frame_b", "b4.frame_a">);
  STATIC_REQUIRE(detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(s)>>());
  test::agree(s, rng);
}

TEST_CASE("Planar joints in a planar scene: the plane's arithmetic") {
  std::mt19937 rng(5152);
  // A PD law on r that reads the first Planar's angle and rate too: its
  // dual numbers take every direction, the Planar's coordinates among them.
  auto pd = [](auto t, const auto& x) {
    using std::cos;
    return -5.0 * (x.q(3) - 0.4 * x.q(2)) - 0.6 * x.v(3) + 0.3 * x.v(0) * cos(t);
  };
  const auto s = scene(World<"world">({.g = {0, -9.81, 0}}), Planar<"p", axis::z, axis::x>{},
                       Body<"b1", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.25).asDiagonal(), .r_cm = {0.2, 0.1, 0}}),
                       revolute<"r", axis::z>(pd), FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
                       Body<"b2", cm::offset>({.m = 0.6, .J = Vec3d(0.01, 0.02, 0.03).asDiagonal(), .r_cm = {0.25, 0, 0}}),
                       Planar<"p2", axis::z, axis::y>{}, Body<"b3">({.m = 0.3, .J = Vec3d(0.01, 0.01, 0.02).asDiagonal()}),
                       connect<"world.frame_b", "p.frame_a">, connect<"p.frame_b", "b1.frame_a">,
                       connect<"p.frame_b", "r.frame_a">, connect<"r.frame_b", "rod.frame_a">,
                       connect<"rod.frame_b", "b2.frame_a">, connect<"rod.frame_b", "p2.frame_a">,
                       connect<"p2.frame_b", "b3.frame_a">);
  using S = std::remove_cvref_t<decltype(s)>;
  STATIC_REQUIRE(detail::planar_axis<S>() == 2);
  STATIC_REQUIRE(detail::jacobian_takes_analytic<S>());
  test::agree(s, rng, 0.9);
}

TEST_CASE("a Universal connected frame_b toward the World takes dual numbers") {
  const auto u = scene(World<"world">{}, Universal<"u">{}, Body<"b">({.m = 1, .J = Mat3d::Identity()}),
                       connect<"world.frame_b", "u.frame_b">, connect<"u.frame_a", "b.frame_a">);
  STATIC_REQUIRE_FALSE(detail::analytic_derivatives<std::remove_cvref_t<decltype(u)>>());
}

// A Cylindrical's turn and slide commute: connected frame_b toward the World
// (its rates in the other order) it is still a row of one-rate nodes.
TEST_CASE("a Cylindrical connected frame_b toward the World: the analytic Jacobian") {
  std::mt19937 rng(907);
  const auto s = scene(World<"world">({.g = {0.4, -9.81, -0.3}}),
                       Cylindrical<"c", axis::any>({.n = Vec3d(0.3, -0.2, 1).normalized()}),
                       Body<"b1", cm::offset>({.m = 1.1, .J = Vec3d(0.02, 0.03, 0.025).asDiagonal(), .r_cm = {0.2, -0.1, 0.1}}),
                       FixedTranslation<"r1">({.d = {0.3, 0.1, -0.2}}),
                       Cylindrical<"c2", axis::y>{},
                       Body<"b2", cm::offset>({.m = 0.6, .J = Vec3d(0.01, 0.012, 0.008).asDiagonal(), .r_cm = {0.1, 0, 0.2}}),
                       Revolute<"j", axis::x>{},
                       Body<"b3", cm::offset>({.m = 0.4, .J = Vec3d(0.004, 0.006, 0.005).asDiagonal(), .r_cm = {0, -0.3, 0}}),
                       connect<"world.frame_b", "c.frame_b">, connect<"c.frame_a", "b1.frame_a">,
                       connect<"c.frame_a", "r1.frame_a">, connect<"r1.frame_b", "c2.frame_b">,
                       connect<"c2.frame_a", "b2.frame_a">, connect<"c2.frame_a", "j.frame_a">,
                       connect<"j.frame_b", "b3.frame_a">);
  STATIC_REQUIRE(detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(s)>>());
  test::agree(s, rng);
}
