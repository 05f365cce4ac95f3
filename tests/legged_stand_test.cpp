// A quadruped (models::legged with feet and a belly) dropped onto the ground:
// under PD drives read by joint name it settles and stands, its base height
// steady and its weight on its four feet; with zero gains its legs give way
// and it comes to rest on its belly, above the ground.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/legged.hpp>

#include <cmath>

using namespace flange;

namespace {
// Below v_t a foot's friction is a viscous μ·f_n·v/v_t: a foot loaded
// sideways creeps until the legs' PD laws take the load off it, with a
// time constant of about (μ·f_n/v_t)/(the leg's stiffness at the foot,
// ~k_p/ℓ²): 0.09 s with v_t = 3 cm/s and k_p = 1000 N m/rad, so that the
// stance is steady to 1e-6 m within a second or two.
const models::legged_params params{.transition_velocity = 0.03};
auto robot(double kp, double kd) { return models::legged<4, 3, true, true>(params, models::crouch_drive{kp, kd}); }
using Robot = decltype(robot(0, 0));

/// Standing at y = 0 in the crouch, its feet 4 cm above the ground.
Robot::state_type crouched(const Robot& s) { return models::crouched_state(s); }

double total_mass() { return params.trunk_mass + 12 * params.link_mass; }

template <class Sol>
double feet_force(const Sol& sol) {
  return sol.template internal<"foot0", "f_n">() + sol.template internal<"foot1", "f_n">() +
         sol.template internal<"foot2", "f_n">() + sol.template internal<"foot3", "f_n">();
}
}  // namespace

TEST_CASE("a quadruped under PD drives read by joint name settles onto its feet and stands") {
  const auto s = robot(1000, 50);
  const auto x0 = crouched(s);
  const auto x2 = simulate(s, x0, 0.0, 2.0, {.tolerance = 1e-9});
  const auto x3 = simulate(s, x2, 2.0, 3.0, {.tolerance = 1e-9});
  const auto sol = recover(s, 3.0, x3);
  const double weight = total_mass() * 9.81, feet = feet_force(sol);
  const double belly = sol.internal<"belly", "δ[0]">();
  INFO("base height " << x2[1] << " m at 2 s, " << x3[1] << " m at 3 s; feet carry " << feet << " N of "
                      << weight << " N");
  CHECK(std::abs(x3[1] - x2[1]) < 1e-6);     // steady
  CHECK(x3[1] < 0);                          // it dropped onto its feet
  CHECK(std::abs(feet - weight) < 1e-6 * weight);  // and stands on them alone
  CHECK(belly == 0);
}

TEST_CASE("a quadruped whose drives have zero gains collapses onto its belly and stays above the ground") {
  const auto s = robot(0, 0);
  const auto x3 = simulate(s, crouched(s), 0.0, 3.0, {.tolerance = 1e-9});
  const auto sol = recover(s, 3.0, x3);
  double belly = 0;
  for (double d : {sol.internal<"belly", "δ[0]">(), sol.internal<"belly", "δ[1]">(), sol.internal<"belly", "δ[4]">(),
                   sol.internal<"belly", "δ[5]">()})
    belly = std::max(belly, d);
  INFO("base height " << x3[1] << " m; the ground at " << -params.ground_depth << " m; belly corners " << belly
                      << " m deep");
  CHECK(belly > 0);                                                  // it lies on its belly
  CHECK(x3[1] > -params.ground_depth);                               // its centre above the ground
  CHECK(x3[1] - params.belly.y() < -params.ground_depth + 1e-3);     // its belly on it
}

TEST_CASE("a diverged state too large for double's products is reported as overflowed, not as a singular mass matrix") {
  // A floating base's quaternion at 1e200: finite, but its squares
  // overflow, and the pivots come out NaN (as explicit Euler's blown-up
  // quadruped did in the work-precision study).
  const auto robot = models::legged<1, 1>();
  decltype(robot)::state_type x{}, dx;
  x[3] = 1e200;
  x[6] = 1e200;
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(robot(x, dx, 0.5), Contains("the state overflowed at t = 0.5") && Contains("diverged") &&
                                           !Contains("singular mass matrix"));
}
