// Branched trees: random shapes (depth up to 4, up to 3 joints on one frame)
// with every joint and force element, planar and spatial. On each, at random
// states and with the stack filled with NaN before every evaluation: the
// derivative against the articulated-body algorithm, the residual on the
// recovered variables, and the power balance (tree_laws.hpp).
#include <algorithm>

#include <catch2/catch.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
/// Whether some frame carries two or more joints: the shape really branches.
constexpr bool branches(const models::tree_shape& s) {
  for (int p = -1; p < s.n; ++p) {
    int k = 0;
    for (int i = 0; i < s.n; ++i) k += s.parent[i] == p;
    if (k >= 2) return true;
  }
  return false;
}

template <unsigned Seed, int N, bool Planar, bool Stops = false>
void check_shape(test::law_errors& worst) {
  constexpr auto shape = models::random_tree_shape(Seed, N, Planar, false, Stops);
  static_assert(branches(shape), "pick a seed whose tree branches");
  std::mt19937 rng(Seed);
  test::law_errors e;
  for (int k = 0; k < 4; ++k) {
    const auto s = models::tree<shape>(test::tree_params<N>(rng));
    static_assert(Planar == (detail::planar_axis<std::remove_cvref_t<decltype(s)>>() >= 0));
    test::check_laws(s, rng, e);
  }
  if constexpr (Stops) {
    static_assert(std::count(shape.stops.begin(), shape.stops.end(), true) >= 2, "pick a seed with stops");
  }
  INFO("seed " << Seed << ", " << N << " joints: NE − ABA " << e.algorithms << ", residual " << e.residual
               << ", power balance " << e.power);
  // Both algorithms solve one well-conditioned system (mass-matrix condition
  // below ~1e4 for these parameters): 1e-10 leaves a wide margin over round-off.
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  // The energy's rate by dual numbers, the powers from recovered values:
  // round-off only, amplified by the same conditioning as q̈.
  CHECK(e.power <= 1e-10);
  worst.algorithms = std::max(worst.algorithms, e.algorithms);
  worst.residual = std::max(worst.residual, e.residual);
  worst.power = std::max(worst.power, e.power);
}
}  // namespace

TEST_CASE("random spatial trees: derivative = articulated-body, residual ≈ 0, power balance") {
  test::law_errors worst;
  check_shape<1, 6, false>(worst);
  check_shape<2, 7, false>(worst);
  check_shape<3, 8, false>(worst);
  WARN("spatial trees: largest NE − ABA " << worst.algorithms << ", residual " << worst.residual << ", power "
                                          << worst.power);
}

TEST_CASE("random planar trees: derivative = articulated-body, residual ≈ 0, power balance") {
  test::law_errors worst;
  check_shape<4, 6, true>(worst);
  check_shape<5, 7, true>(worst);
  check_shape<6, 8, true>(worst);
  WARN("planar trees: largest NE − ABA " << worst.algorithms << ", residual " << worst.residual << ", power "
                                         << worst.power);
}

TEST_CASE("random trees with joint stops: derivative = articulated-body, residual ≈ 0, power balance") {
  // axis_law::limited around every kind of law; random_state's coordinates
  // (±1.5) press on the stops (bounds within ±1.2) most of the time.
  test::law_errors worst;
  check_shape<11, 7, false, true>(worst);
  check_shape<12, 6, true, true>(worst);
  WARN("trees with stops: largest NE − ABA " << worst.algorithms << ", residual " << worst.residual << ", power "
                                             << worst.power);
}
