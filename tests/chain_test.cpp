// Larger trees: a planar chain with compile-time axes and a spatial chain with
// non-parallel run-time axes. Newton–Euler with the mass matrix against the
// articulated-body algorithm, and the residual on the recovered solution.
#include <catch2/catch.hpp>
#include <flange/dynamics/articulated_body.hpp>
#include <flange/dynamics/recover.hpp>

#include "random_params.hpp"

using namespace flange;

template <int N, template <int> class Axes>
void check_chain(std::mt19937& rng) {
  const auto p = test::chain_params<N>(rng);
  const auto chain = models::chain<N, Axes>(p);
  for (int k = 0; k < 20; ++k) {
    std::array<double, 2 * N> x, dx;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    chain(x, dx, 0.0);
    std::array<double, N> aba;
    accelerations_articulated_body(chain, 0.0, x.data(), x.data() + N, aba.data());
    double scale = 1, diff = 0;
    for (int i = 0; i < N; ++i) {
      scale = std::max(scale, std::abs(dx[N + i]));
      diff = std::max(diff, std::abs(aba[i] - dx[N + i]));
    }
    INFO("N = " << N << ", sample " << k);
    // Both solve the same linear system; a condition number of the mass matrix
    // up to ~1e4 for these chains leaves 1e-10 a wide margin over 1e-16.
    CHECK(diff <= 1e-10 * scale);
    const auto sol = recover(chain, 0.0, x);
    CHECK(scaled_residual(chain, sol) < 1e-12);
  }
}

TEST_CASE("a planar chain of 1 to 8 links: both algorithms agree") {
  std::mt19937 rng(11);
  check_chain<1, models::planar_axes>(rng);
  check_chain<2, models::planar_axes>(rng);
  check_chain<5, models::planar_axes>(rng);
  check_chain<8, models::planar_axes>(rng);
}

TEST_CASE("a spatial chain with non-parallel axes: both algorithms agree") {
  std::mt19937 rng(12);
  check_chain<3, models::runtime_axes>(rng);
  check_chain<8, models::runtime_axes>(rng);
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
