// The generated derivative against the paper's closed-form equations of motion,
// at random states and random parameter sets.
#include <catch2/catch.hpp>
#include <flange/dynamics/articulated_body.hpp>
#include <flange/dynamics/newton_euler.hpp>

#include "random_params.hpp"

using namespace flange;

TEST_CASE("the robot arm's generated derivative is the paper's (J_z + m d²) θ̈ + m d g sin θ = M_z") {
  std::mt19937 rng(1);
  int checked = 0;
  for (int set = 0; set < 20; ++set) {
    const auto p = test::arm_params(rng);
    const double Mz = test::uniform(rng, -20, 20);
    const auto arm = models::robot_arm(p, Vec3d(0, 0, Mz));
    for (int k = 0; k < 10; ++k, ++checked) {
      const std::array<double, 2> x{test::uniform(rng, -10, 10), test::uniform(rng, -10, 10)};
      std::array<double, 2> dx;
      arm(x, dx, 0.0);
      const double ref = models::robot_arm_theta_dd(p, Mz, x[0] + M_PI / 2);
      // Relative to the size of the terms: 1e-12 leaves room for the few
      // roundings of each and for sin(φ + π/2) = cos φ being rounded.
      const double scale = (std::abs(Mz) + p.m * p.d * p.g) / (p.Jz + p.m * p.d * p.d);
      INFO("set " << set << " φ = " << x[0] << " φ̇ = " << x[1]);
      CHECK(std::abs(dx[1] - ref) <= 1e-12 * scale);
      CHECK(dx[0] == x[1]);
    }
  }
  CHECK(checked >= 100);
}

TEST_CASE("the gantry crane's generated derivative is the paper's standard form") {
  std::mt19937 rng(2);
  int checked = 0;
  for (int set = 0; set < 20; ++set) {
    const auto p = test::crane_params(rng);
    const double f = test::uniform(rng, -20, 20);
    const auto crane = models::gantry_crane(p, f);
    for (int k = 0; k < 10; ++k, ++checked) {
      const std::array<double, 4> x{test::uniform(rng, -5, 5), test::uniform(rng, -10, 10),
                                    test::uniform(rng, -5, 5), test::uniform(rng, -10, 10)};
      std::array<double, 4> dx;
      crane(x, dx, 0.0);
      const auto ref = models::gantry_crane_accelerations(p, f, x[1] + M_PI / 2, x[3]);
      const double num = std::abs(f) + (p.g + p.d * x[3] * x[3]) * (p.m + p.M);
      const double den = p.M + p.m * std::pow(std::sin(x[1] + M_PI / 2), 2);
      INFO("set " << set << " s = " << x[0] << " φ = " << x[1] << " ṡ = " << x[2] << " φ̇ = " << x[3]);
      CHECK(std::abs(dx[2] - ref.s_dd) <= 1e-12 * num / den);
      CHECK(std::abs(dx[3] - ref.theta_dd) <= 1e-12 * num / (p.d * den));
    }
  }
  CHECK(checked >= 100);
}

TEST_CASE("the articulated-body algorithm agrees on the paper's scenes") {
  std::mt19937 rng(3);
  for (int k = 0; k < 100; ++k) {
    const auto crane = models::gantry_crane(test::crane_params(rng), test::uniform(rng, -5, 5));
    const std::array<double, 4> x{test::uniform(rng, -5, 5), test::uniform(rng, -10, 10),
                                  test::uniform(rng, -5, 5), test::uniform(rng, -10, 10)};
    std::array<double, 4> dx;
    std::array<double, 2> aba;
    crane(x, dx, 0.0);
    accelerations_articulated_body(crane, 0.0, x.data(), x.data() + 2, aba.data());
    const double scale = 1 + std::abs(dx[2]) + std::abs(dx[3]);
    CHECK(std::abs(aba[0] - dx[2]) <= 1e-12 * scale);
    CHECK(std::abs(aba[1] - dx[3]) <= 1e-12 * scale);
  }
}

TEST_CASE("the crane's mass matrix is the paper's: [[m+M, -m d sin φ], [-m d sin φ, m d²]]") {
  // The paper's reduced equations (m+M)·s̈ − (m d sin φ)·φ̈ = … and, times m·d,
  // (−m d sin φ)·s̈ + m d²·φ̈ = …: a symmetric mass matrix with these entries.
  std::mt19937 rng(4);
  for (int k = 0; k < 50; ++k) {
    const auto p = test::crane_params(rng);
    const auto crane = models::gantry_crane(p);
    const std::array<double, 2> q{test::uniform(rng, -3, 3), test::uniform(rng, -4, 4)};
    const auto M = mass_matrix(crane, q.data());
    const double s = std::sin(q[1]);
    const double scale = p.m + p.M + p.m * p.d * p.d;
    CHECK(std::abs(M(0, 0) - (p.m + p.M)) <= 1e-13 * scale);
    CHECK(std::abs(M(0, 1) + p.m * p.d * s) <= 1e-13 * scale);
    CHECK(std::abs(M(1, 0) - M(0, 1)) == 0.0);
    CHECK(std::abs(M(1, 1) - p.m * p.d * p.d) <= 1e-13 * scale);
  }
}
