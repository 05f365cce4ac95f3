// A URDF whose link and joint names hold '.' and a space, as exported files
// write them: flange-urdf imports it under names flange can hold
// ("upper_arm.001" -> "upper_arm_001"), and the scene simulates: a double
// pendulum in the x–z plane (joints about y) whose energy is conserved.
#include <cmath>

#include <catch2/catch.hpp>
#include <flange/flange.hpp>

#include "dotted.hpp"

using namespace flange;

TEST_CASE("a URDF with dotted names imports under flange names and simulates") {
  const auto robot = dotted::make_scene();
  using S = decltype(robot);
  static_assert(S::n_q == 2);
  static_assert(S::q_offset<"shoulder_joint">() == 0 && S::q_offset<"elbow_joint">() == 1);
  const auto b = bodies(robot);
  REQUIRE(b.size() == 2);
  CHECK(b[0].name == "upper_arm_001");
  CHECK(b[1].name == "fore_arm_002");
  const auto x0 = initial_state<"shoulder_joint", "elbow_joint">(robot, {.q = 0.4}, {.q = -0.8, .v = 2});
  const auto x1 = simulate(robot, x0, 0.0, 2.0, {.tolerance = 1e-11});
  // Undamped, undriven: the energy stays what it was, to the stepper's error.
  const double e0 = energy(robot, 0.0, x0).total(), e1 = energy(robot, 2.0, x1).total();
  CHECK(std::abs(e1 - e0) < 1e-8 * (1 + std::abs(e0)));
  CHECK(std::abs(x1[0] - x0[0]) > 1e-3);  // it moved
}
