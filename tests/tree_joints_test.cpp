// Random trees mixing every joint kind (Revolute, Prismatic, Spherical,
// Universal, Cylindrical, Planar, FreeMotion), with every force element, at
// random states with the stack filled with NaN: the derivative against the
// articulated-body algorithm, the residual on the recovered variables and
// the power balance (tree_laws.hpp).
#include <catch2/catch.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
template <unsigned Seed, int N, bool Planar>
void check_shape(test::law_errors& worst) {
  constexpr auto shape = models::random_tree_shape(Seed, N, Planar, true);
  std::mt19937 rng(Seed);
  test::law_errors e;
  for (int k = 0; k < 3; ++k) {
    const auto s = models::tree<shape>(test::tree_params<N>(rng));
    static_assert(Planar == (detail::planar_axis<std::remove_cvref_t<decltype(s)>>() >= 0));
    test::check_laws(s, rng, e);
  }
  INFO("seed " << Seed << ", " << N << " joints: NE − ABA " << e.algorithms << ", residual " << e.residual
               << ", power balance " << e.power);
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);
  worst.algorithms = std::max(worst.algorithms, e.algorithms);
  worst.residual = std::max(worst.residual, e.residual);
  worst.power = std::max(worst.power, e.power);
}

/// How many joints of each kind a shape has (revolute: Revolute or Prismatic).
constexpr std::array<int, models::n_joint_kinds> kinds(const models::tree_shape& s) {
  std::array<int, models::n_joint_kinds> k{};
  for (int i = 0; i < s.n; ++i) ++k[int(s.kind[i])];
  return k;
}
}  // namespace

TEST_CASE("random spatial trees of every joint kind: derivative = articulated-body, residual ≈ 0, power balance") {
  // Together the shapes hold every kind.
  constexpr auto a = kinds(models::random_tree_shape(31, 8, false, true));
  constexpr auto b = kinds(models::random_tree_shape(32, 8, false, true));
  constexpr auto c = kinds(models::random_tree_shape(33, 8, false, true));
  for (int k = int(models::joint_kind::spherical); k < models::n_joint_kinds; ++k) CHECK(a[k] + b[k] + c[k] > 0);
  test::law_errors worst;
  check_shape<31, 8, false>(worst);
  check_shape<32, 8, false>(worst);
  check_shape<33, 8, false>(worst);
  WARN("spatial trees of every joint kind: largest NE − ABA " << worst.algorithms << ", residual " << worst.residual
                                                              << ", power " << worst.power);
}

TEST_CASE("random planar trees with Planar joints: derivative = articulated-body, residual ≈ 0, power balance") {
  constexpr auto a = kinds(models::random_tree_shape(34, 7, true, true));
  constexpr auto b = kinds(models::random_tree_shape(35, 7, true, true));
  CHECK(a[5] + b[5] > 0);
  test::law_errors worst;
  check_shape<34, 7, true>(worst);
  check_shape<35, 7, true>(worst);
  WARN("planar trees with Planar joints: largest NE − ABA " << worst.algorithms << ", residual " << worst.residual
                                                            << ", power " << worst.power);
}
