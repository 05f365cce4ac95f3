// Hard case for branched trees: masses spread over twelve orders of
// magnitude (1e-6 to 1e6 kg), which make the mass matrix's condition reach
// 1e14, checked against the second algorithm, the residual and the power
// balance to round-off times cond(M).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <flange/dynamics/energy_mass_matrix.hpp>
#include <flange/equations_of_motion.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {
/// A random tree of every joint kind and force element (models/tree.hpp)
/// whose bodies' masses and inertias are scaled by 10^k, k from −6 to 6
/// along the tree; returns the largest cond(M) met.
template <unsigned Seed>
double mass_ratio_tree() {
  constexpr int n = 6;
  constexpr auto shape = models::random_tree_shape(Seed, n, false, true);
  std::mt19937 rng(Seed);
  auto p = test::tree_params<n>(rng);
  for (int i = 0; i < n; ++i) {
    const double scale = std::pow(10.0, -6 + 12.0 * ((i * 5 + int(Seed)) % n) / (n - 1));
    p.m[i] *= scale;
    p.J[i] *= scale;
  }
  const auto s = models::tree<shape>(p);
  using S = std::remove_const_t<decltype(s)>;
  // The two algorithms, the residual and the power balance, at states whose
  // conditioning is measured there.
  double worst_cond = 0;
  for (int k = 0; k < 10; ++k) {
    const auto x = test::random_state(s, rng);
    const double cond = mass_matrix_condition(s, x);
    worst_cond = std::max(worst_cond, cond);
    typename S::state_type dx;
    s(x, dx, 0.2);
    std::array<double, S::n_v> aba;  // the other algorithm
    accelerations_other(s, 0.2, x.data(), x.data() + S::n_q, aba.data());
    double scale = 1, err = 0;
    for (int i = 0; i < S::n_v; ++i) scale = std::max(scale, std::abs(dx[S::n_q + i]));
    for (int i = 0; i < S::n_v; ++i) err = std::max(err, std::abs(aba[i] - dx[S::n_q + i]) / scale);
    const double residual = scaled_residual(s, recover(s, 0.2, x));
    const auto [gap, pscale] = test::power_balance(s, 0.2, x);
    INFO("seed " << Seed << ", cond(M) " << cond << ": NE − ABA " << err << ", residual " << residual << ", power "
                 << std::abs(gap) / pscale);
    CHECK(err <= 1e-15 * cond * 10);
    CHECK(residual <= std::max(1e-12, 1e-15 * cond * 10));
    CHECK(std::abs(gap) / pscale <= std::max(1e-10, 1e-15 * cond * 10));
  }
  return worst_cond;
}
}  // namespace

TEST_CASE("trees with masses from 1e-6 to 1e6 kg keep their laws, to round-off times cond(M)") {
  // Masses and inertias over twelve orders of magnitude make cond(M) reach
  // 1e9 and more. Round-off in either algorithm is about ε·cond(M) relative
  // in q̈, so Newton–Euler + mass matrix and the articulated-body algorithm
  // must agree to 1e-15·cond(M) (with a factor 10 for the sums), and so must
  // the power balance, whose dE/dt carries q̈'s error (its usual bound, 1e-10,
  // where that is larger). So must the residual (its usual bound, 1e-12, where
  // that is larger): on these trees of free and spherical joints the cost
  // model picks the articulated body (dynamics/algorithm.hpp), whose q̈ is
  // accurate to ε·cond(M) but does not make M·q̈ − (τ − b) small by
  // construction, as LDLᵀ's backward-stable solve does; the residual
  // evaluates exactly that (measured: up to 3e-8 at cond(M) 1e14).
  const double worst_cond = std::max({mass_ratio_tree<3>(), mass_ratio_tree<5>(), mass_ratio_tree<8>()});
  WARN("largest cond(M) over the mass-ratio trees: " << worst_cond);
  CHECK(worst_cond > 1e9);  // the case is as hard as it says
}

TEST_CASE("a heavy body flying on a FreeMotion joint from a 1e-6 kg link: the articulated-body algorithm stays exact") {
  // A free joint with no force of its own passes its parent nothing: the
  // hinge moves exactly as the light link alone would (the reference: the
  // same scene without the free body). The articulated-body algorithm used
  // to compute that zero as IA − U·D⁻¹·Uᵀ, whose round-off (of the heavy
  // body) swamped the light parent and made its articulated inertia negative
  // ("singular articulated inertia" at a regular state, found by the case
  // above); the zero is now exact, so it agrees with the reference to
  // round-off whatever the ratio. The default Newton–Euler + mass matrix
  // cannot do that: the hinge's pivot is the light inertia left after
  // subtracting two heavy ones, so its error is ε·cond(M), and where that
  // leaves fewer than about three digits its pivot test refuses the state
  // (docs/hard-cases.md; #15 chooses the algorithm per scene).
  const Vec3d n(0.3, 0.2, 1.0);
  const Mat3d J_light = 1e-8 * Mat3d::Identity();
  const auto light_only = scene(World<"world">{}, Revolute<"hinge">({.n = n}), FixedTranslation<"arm">({.d = {0.4, 0.1, 0}}),
                                Body<"light">({.m = 1e-6, .J = J_light}), connect<"world.frame_b", "hinge.frame_a">,
                                connect<"hinge.frame_b", "arm.frame_a">, connect<"arm.frame_b", "light.frame_a">);
  for (double heavy : {1.0, 1e6, 1e12}) {
    const auto s = scene(World<"world">{}, Revolute<"hinge">({.n = n}), FixedTranslation<"arm">({.d = {0.4, 0.1, 0}}),
                         Body<"light">({.m = 1e-6, .J = J_light}), FreeMotion<"fly">{},
                         Body<"heavy", cm::offset>({.m = heavy, .J = heavy * Vec3d(0.1, 0.2, 0.25).asDiagonal(),
                                                     .r_cm = {0.05, -0.02, 0.1}}),
                         connect<"world.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "arm.frame_a">,
                         connect<"arm.frame_b", "light.frame_a">, connect<"arm.frame_b", "fly.frame_a">,
                         connect<"fly.frame_b", "heavy.frame_a">);
    using S = decltype(s);
    std::mt19937 rng(9);
    double worst_aba = 0, worst_default = 0;
    int refused = 0;
    for (int k = 0; k < 10; ++k) {
      const auto x = test::random_state(s, rng);
      std::array<double, 2> xr{x[0], x[S::n_q]}, dr;
      light_only(xr, dr, 0.0);
      std::array<double, S::n_v> aba;
      accelerations_articulated_body(s, 0.0, x.data(), x.data() + S::n_q, aba.data());
      const double scale = std::max(1.0, std::abs(dr[1]));
      worst_aba = std::max(worst_aba, std::abs(aba[0] - dr[1]) / scale);
      typename S::state_type dx;
      try {
        s(x, dx, 0.0);
        const double err = std::abs(dx[S::n_q] - dr[1]) / scale, cond = mass_matrix_condition(s, x);
        worst_default = std::max(worst_default, err);
        INFO("heavy " << heavy << " kg: Newton–Euler + mass matrix off by " << err << " at cond(M) " << cond);
        CHECK(err <= 1e-15 * cond * 10);
      } catch (const simulation_error& e) {
        ++refused;
        CHECK(std::string(e.what()).find("singular mass matrix") != std::string::npos);
      }
    }
    WARN("heavy body " << heavy << " kg: articulated body off by " << worst_aba << "; Newton–Euler + mass matrix off by "
                       << worst_default << ", refused " << refused << " of 10 states");
    CHECK(worst_aba <= 1e-12);
  }
}
