// The analytic Jacobian (dynamics/derivatives.hpp) of random branched trees
// that mix balls (Spherical, FreeMotion: anywhere in the tree, under and over
// one-axis joints) with Revolute and Prismatic joints, axis laws, offsets,
// every body kind and every force element of models/tree.hpp: against the
// dual-number Jacobian of the same scene and central differences
// (jacobian_agree.hpp). The joints of rates in series (Universal,
// Cylindrical, Planar) are drawn as balls here (jacobian_series_test.cpp
// keeps them), and a ball faces the World with its frame_a;
// tests/jacobian_ball_test.cpp has the hand-built scenes.
#include <catch2/catch.hpp>

#include <flange/models/tree.hpp>
#include <flange/simulate/jacobian.hpp>

#include "jacobian_agree.hpp"

using namespace flange;

namespace {
/// random_tree_shape with every joint kind, the kinds of more than one
/// axis that are not balls turned into Spherical joints, balls frame_a toward
/// the World; with or without force elements.
template <unsigned Seed, int N, bool Loads>
constexpr models::tree_shape ball_tree() {
  auto t = models::random_tree_shape(Seed, N, false, true);
  for (int i = 0; i < t.n; ++i) {
    using models::joint_kind;
    const joint_kind k = t.kind[i];
    if (k == joint_kind::universal || k == joint_kind::cylindrical || k == joint_kind::planar)
      t.kind[i] = joint_kind::spherical;
    if (t.kind[i] == joint_kind::spherical || t.kind[i] == joint_kind::free_motion) t.reversed[i] = false;
  }
  return Loads ? t : test::without_force_elements(t);
}

/// How many joints of the shape are balls.
constexpr int balls(const models::tree_shape& t) {
  int n = 0;
  for (int i = 0; i < t.n; ++i)
    n += t.kind[i] == models::joint_kind::spherical || t.kind[i] == models::joint_kind::free_motion;
  return n;
}
}  // namespace

TEST_CASE("random trees with balls: the analytic Jacobian equals the dual-number Jacobian") {
  std::mt19937 rng(4903);
  auto check = [&]<unsigned Seed, int N, bool Loads>() {
    constexpr auto shape = ball_tree<Seed, N, Loads>();
    static_assert(balls(shape) >= 2, "each tree should mix balls with one-axis joints");
    static_assert(balls(shape) < N, "each tree should mix balls with one-axis joints");
    const auto s = models::tree<shape>(test::tree_params<shape.n>(rng));
    STATIC_REQUIRE(detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(s)>>());
    INFO("tree seed " << Seed << ", " << N << " joints, " << balls(shape) << " balls"
                      << (Loads ? ", force elements" : ""));
    test::agree(s, rng);
  };
  check.operator()<30, 7, false>();  // a FreeMotion, three Spherical joints, three one-axis joints
  check.operator()<34, 7, true>();   // a FreeMotion, two Spherical joints, four one-axis joints
}
