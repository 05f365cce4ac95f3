// The dynamics are templated on the scalar: long double runs the same code,
// agrees with double to double's precision, and is more precise.
#include <catch2/catch.hpp>
#include <flange/simulate/odeint.hpp>

#include "random_params.hpp"

using namespace flange;

TEST_CASE("the derivative in long double agrees with double") {
  std::mt19937 rng(9);
  const auto chain = models::chain<4, models::runtime_axes>(test::chain_params<4>(rng));
  for (int k = 0; k < 20; ++k) {
    std::array<double, 8> x, dx;
    std::array<long double, 8> xl, dxl;
    for (int i = 0; i < 8; ++i) xl[i] = x[i] = test::uniform(rng, -2, 2);
    chain(x, dx, 0.0);
    chain(xl, dxl, 0.0L);
    for (int i = 4; i < 8; ++i) CHECK(std::abs(static_cast<double>(dxl[i]) - dx[i]) <= 1e-12 * (1 + std::abs(dx[i])));
  }
}

TEST_CASE("the derivative of a branched tree in long double agrees with double") {
  std::mt19937 rng(10);
  constexpr auto shape = models::random_tree_shape(3, 8, false);
  const auto tree = models::tree<shape>(test::tree_params<shape.n>(rng));
  constexpr int n = 2 * shape.n;
  for (int k = 0; k < 20; ++k) {
    std::array<double, n> x, dx;
    std::array<long double, n> xl, dxl;
    for (int i = 0; i < n; ++i) xl[i] = x[i] = test::uniform(rng, -1, 1);
    tree(x, dx, 0.0);
    tree(xl, dxl, 0.0L);
    for (int i = shape.n; i < n; ++i)
      CHECK(std::abs(static_cast<double>(dxl[i]) - dx[i]) <= 1e-12 * (1 + std::abs(dx[i])));
  }
}

TEST_CASE("a long-double simulation conserves energy better than double can") {
  const auto arm = models::robot_arm();
  using L = std::array<long double, 2>;
  L x{1.0L, 0.0L};
  const long double e0 = recover(arm, 0.0L, x).energy();
  odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_fehlberg78<L, long double>>(1e-17L, 1e-17L),
                             arm, x, 0.0L, 10.0L, 1e-3L);
  const long double drift = std::abs(recover(arm, 10.0L, x).energy() - e0) / std::abs(e0);
  INFO("relative energy drift " << static_cast<double>(drift));
  // Below double's 2.2e-16: only a long-double computation gets there.
  CHECK(drift < 1e-16L);
}
