// A joint may be connected either way round. With frame_b toward the World the
// joint's motion is reversed, which is the same as turning its axis round; the
// derivative must equal that of the forward scene with axis −n, and the
// residual must vanish on the recovered solution (its flows come from the
// joint's equations solved in the other direction).
#include <catch2/catch.hpp>
#include <flange/dynamics/recover.hpp>

#include "random_params.hpp"

using namespace flange;

TEST_CASE("a revolute joint with frame_b toward the World is the forward joint with axis −n") {
  const double Mz = 0.7;
  const Mat3d J = Vec3d(0.01, 0.02, 0.02).asDiagonal();
  auto arm = [&](auto joint, auto... connections) {
    return scene(World<"world">{}, Torque<"motor">({.M_ext = Vec3d(0, 0, Mz)}), joint,
                 FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1.0, .J = J}),
                 connect<"world.frame_b", "motor.frame_a">, connect<"rod.frame_b", "mass.frame_a">, connections...);
  };
  const auto reversed = arm(Revolute<"joint", axis::z>{}, connect<"world.frame_b", "joint.frame_b">,
                            connect<"joint.frame_a", "rod.frame_a">, connect<"joint.frame_a", "motor.frame_b">);
  const auto forward = arm(Revolute<"joint">({.n = {0, 0, -1}}), connect<"world.frame_b", "joint.frame_a">,
                           connect<"joint.frame_b", "rod.frame_a">, connect<"joint.frame_b", "motor.frame_b">);
  static_assert(decltype(reversed)::tree.link_dir[1] == -1);
  std::mt19937 rng(7);
  for (int k = 0; k < 50; ++k) {
    const std::array<double, 2> x{test::uniform(rng, -4, 4), test::uniform(rng, -4, 4)};
    std::array<double, 2> a, b;
    reversed(x, a, 0.0);
    forward(x, b, 0.0);
    CHECK(std::abs(a[1] - b[1]) <= 1e-13 * (1 + std::abs(b[1])));
    CHECK(scaled_residual(reversed, recover(reversed, 0.0, x)) < 1e-13);
  }
}

TEST_CASE("a prismatic joint with frame_b toward the World is the forward joint with axis −n") {
  auto crane = [&](auto rail, auto... connections) {
    return scene(World<"world">{}, rail, Body<"cart">({.m = 2.0, .J = Mat3d::Identity()}),
                 Revolute<"pivot", axis::z>{}, FixedTranslation<"rope">({.d = {1.0, 0, 0}}),
                 Body<"load">({.m = 0.5}), connect<"pivot.frame_b", "rope.frame_a">,
                 connect<"rope.frame_b", "load.frame_a">, connections...);
  };
  const auto reversed = crane(Prismatic<"rail", axis::x>({.f = 1.5}), connect<"world.frame_b", "rail.frame_b">,
                              connect<"rail.frame_a", "cart.frame_a">, connect<"rail.frame_a", "pivot.frame_a">);
  const auto forward = crane(Prismatic<"rail">({.n = {-1, 0, 0}, .f = 1.5}), connect<"world.frame_b", "rail.frame_a">,
                             connect<"rail.frame_b", "cart.frame_a">, connect<"rail.frame_b", "pivot.frame_a">);
  std::mt19937 rng(8);
  for (int k = 0; k < 50; ++k) {
    std::array<double, 4> x, a, b;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    reversed(x, a, 0.0);
    forward(x, b, 0.0);
    for (int i = 2; i < 4; ++i) CHECK(std::abs(a[i] - b[i]) <= 1e-13 * (1 + std::abs(b[i])));
    CHECK(scaled_residual(reversed, recover(reversed, 0.0, x)) < 1e-13);
  }
}
