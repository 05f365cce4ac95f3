// The laws of tree_laws.hpp over a list of scene shapes: planar chains with
// compile-time axes, spatial chains with non-parallel run-time axes, and
// branched trees of both kinds (derivative = articulated-body, residual ≈ 0,
// power balance), with the stack filled with NaN before each evaluation.
#include <catch2/catch.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
template <class S>
void check(const S& s, std::mt19937& rng, const char* what) {
  test::law_errors e;
  test::check_laws(s, rng, e, 20);
  INFO(what << ": NE − ABA " << e.algorithms << ", residual " << e.residual << ", power " << e.power);
  // Both solve the same linear system; a condition number of the mass matrix
  // up to ~1e4 for these scenes leaves 1e-10 a wide margin over 1e-16.
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);  // the energy's rate by dual numbers: round-off, amplified like q̈
}
}  // namespace

TEST_CASE("planar shapes: chains of 1 to 8 links and a branched tree obey the laws") {
  std::mt19937 rng(11);
  check(models::chain<1, models::planar_axes>(test::chain_params<1>(rng)), rng, "planar chain of 1");
  check(models::chain<2, models::planar_axes>(test::chain_params<2>(rng)), rng, "planar chain of 2");
  check(models::chain<5, models::planar_axes>(test::chain_params<5>(rng)), rng, "planar chain of 5");
  check(models::chain<8, models::planar_axes>(test::chain_params<8>(rng)), rng, "planar chain of 8");
  constexpr auto tree = models::random_tree_shape(7, 6, true);
  check(models::tree<tree>(test::tree_params<tree.n>(rng)), rng, "planar tree of 6");
}

TEST_CASE("spatial shapes: chains with non-parallel axes and a branched tree obey the laws") {
  std::mt19937 rng(12);
  check(models::chain<3, models::runtime_axes>(test::chain_params<3>(rng)), rng, "spatial chain of 3");
  check(models::chain<8, models::runtime_axes>(test::chain_params<8>(rng)), rng, "spatial chain of 8");
  constexpr auto tree = models::random_tree_shape(8, 6, false);
  check(models::tree<tree>(test::tree_params<tree.n>(rng)), rng, "spatial tree of 6");
}

TEST_CASE("a planar chain with compile-time axes equals the same chain with run-time axes") {
  std::mt19937 rng(13);
  auto p = test::chain_params<4>(rng);
  for (auto& n : p.axis) n = Vec3d::UnitZ();
  const auto fixed = models::chain<4, models::planar_axes>(p);
  const auto general = models::chain<4, models::runtime_axes>(p);
  for (int k = 0; k < 20; ++k) {
    std::array<double, 8> x, a, b;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    fixed(x, a, 0.0);
    general(x, b, 0.0);
    for (int i = 4; i < 8; ++i) CHECK(std::abs(a[i] - b[i]) <= 1e-12 * (1 + std::abs(b[i])));
  }
}

TEST_CASE("a branched tree with compile-time axes equals the same tree with run-time axes") {
  // The same shape, every axis turned into axis::any with the same numbers.
  static constexpr auto typed = models::random_tree_shape(9, 7, false);
  static constexpr auto general = [] {
    auto s = models::random_tree_shape(9, 7, false);
    for (int i = 0; i < s.n; ++i) s.axis[i] = 3;
    return s;
  }();
  std::mt19937 rng(14);
  auto p = test::tree_params<typed.n>(rng);
  for (int i = 0; i < typed.n; ++i)
    if (typed.axis[i] < 3) p.axis[i] = Vec3d::Unit(typed.axis[i]);
  const auto a = models::tree<typed>(p);
  const auto b = models::tree<general>(p);
  for (int k = 0; k < 20; ++k) {
    decltype(a)::state_type x, da, db;
    for (auto& v : x) v = test::uniform(rng, -2, 2);
    a(x, da, 0.0);
    b(x, db, 0.0);
    for (int i = typed.n; i < 2 * typed.n; ++i) CHECK(std::abs(da[i] - db[i]) <= 1e-12 * (1 + std::abs(db[i])));
  }
}
