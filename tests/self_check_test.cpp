// The main self-check: along simulated trajectories of both paper scenes, the
// residual of the components' equations, evaluated on everything recovered
// from (t, x), stays below 1e-9 (scaled) at every sample.
#include <catch2/catch.hpp>
#include <flange/models/paper.hpp>
#include <flange/simulate/odeint.hpp>

using namespace flange;

namespace {
/// Simulates 5 s with dense-output dopri5 at 1e-10 from x0, sampling every
/// 10 ms, and returns the number of samples and the worst scaled residual.
template <class S>
std::pair<int, double> worst_residual_along(const S& scene, typename S::state_type x) {
  int samples = 0;
  double worst = 0;
  odeint::integrate_const(odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<typename S::state_type>()),
                          scene, x, 0.0, 5.0, 0.01, record(scene, [&](const auto& sol) {
                            ++samples;
                            worst = std::max(worst, scaled_residual(scene, sol));
                          }));
  return {samples, worst};
}
}  // namespace

TEST_CASE("the robot arm under a PD law satisfies its 106 equations along the trajectory") {
  auto pd = [](double t, const joint_state<double>& x) {
    return Vec3d(0, 0, -20.0 * (x.q(0) - std::sin(t)) - 2.0 * x.v(0));
  };
  const auto arm = models::robot_arm({}, pd);
  const auto [samples, worst] = worst_residual_along(arm, {-1.0, 0.0});
  INFO("worst scaled residual " << worst);
  CHECK(samples == 501);
  CHECK(worst < 1e-9);
}

TEST_CASE("the gantry crane under a time-varying force satisfies its 125 equations along the trajectory") {
  const auto crane = models::gantry_crane({}, [](double t) { return 5.0 * std::sin(3.0 * t); });
  const auto [samples, worst] = worst_residual_along(crane, {0.0, -1.0, 0.0, 0.0});
  INFO("worst scaled residual " << worst);
  CHECK(samples == 501);
  CHECK(worst < 1e-9);
}

TEST_CASE("a wrong derivative is caught by the residual") {
  // The check can fail: perturb q̈ in the recovered solution and the body's
  // and joint's equations no longer hold.
  const auto arm = models::robot_arm({}, Vec3d(0, 0, 1.0));
  auto sol = recover(arm, 0.0, std::array<double, 2>{0.4, 1.0});
  constexpr int mass = decltype(arm)::index_of("mass");
  CHECK(scaled_residual(arm, sol) < 1e-12);
  // An error of 1e-5 in ω̇ (relative 1e-6 of q̈ here) is ten times over the
  // 1e-9 threshold the trajectory checks use.
  sol.yd(decltype(arm)::slot_offset<mass>(5) + 2) += 1e-5;
  CHECK(scaled_residual(arm, sol) > 1e-8);
}
