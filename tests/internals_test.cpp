// Recovered internal variables read by name, resolved at compile time:
// sol.internal<"component", "variable">() against the same quantity computed
// independently (the buffer's law from the frames' positions, the joint's
// angle and rotation from the state).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <flange/equations_of_motion.hpp>
#include <flange/models/controlled_crane.hpp>

using namespace flange;

TEST_CASE("internals by name: a spring-damper's length and tension, a joint's angle and rotation") {
  models::controlled_crane_params p;
  const auto crane = models::controlled_crane(p);
  const decltype(crane)::state_type x{0.3, -1.2, 0.7, -0.4};
  const auto sol = recover(crane, 0.0, x);
  // The buffer runs from the rail's end (−1.5, 0, 0) to the cart at s.
  const double len = std::abs(x[0] - (-(p.buffer_s0 + 0.5)));
  const double rate = x[2];  // the length grows with ṡ
  CHECK(std::abs(sol.internal<"buffer", "s">() - len) < 1e-15);
  CHECK(std::abs(sol.internal<"buffer", "f">() - (p.buffer_c * (len - p.buffer_s0) + p.buffer_d * rate)) < 1e-12);
  CHECK(std::abs(sol.internal_rate<"buffer", "s">() - rate) < 1e-15);
  CHECK(sol.internal<"pivot", "φ">() == x[1]);
  CHECK(sol.internal_rate<"pivot", "φ">() == x[3]);
  CHECK(sol.internal<"rail", "s">() == x[0]);
  const Mat3d R = sol.internal<"pivot", "R_rel">();
  CHECK((R - axis_rotation<double>(Vec3d::UnitZ(), x[1])).cwiseAbs().maxCoeff() < 1e-15);
}
