// flange-urdf turns a URDF <limit lower upper> into compliant stops
// (axis_law::limited): the example arm released under gravity stays within
// its limits, as far as the energy it can release allows, where the same
// arm imported with --no-limits swings through them.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/odeint.hpp>

#include "spatial_arm_limited.hpp"
#include "spatial_arm_unlimited.hpp"

using namespace flange;

namespace {
/// The largest distance past the elbow's (±2.6 rad) or the wrist's (±2 rad)
/// limit over 4 s, released level and at rest with the shoulder turning.
template <class S>
double worst_overrun(const S& s) {
  using X = typename S::state_type;
  X x{};
  x[S::n_q + S::v_offset("shoulder")] = 1.0;
  double worst = -10;
  for (int k = 1; k <= 400; ++k) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), s, x,
                               0.01 * (k - 1), 0.01 * k, 1e-4);
    worst = std::max({worst, std::abs(x[S::q_offset("elbow")]) - 2.6, std::abs(x[S::q_offset("wrist")]) - 2.0});
  }
  return worst;
}
}  // namespace

TEST_CASE("a URDF arm released under gravity stays within its joint limits") {
  const double limited = worst_overrun(spatial_arm_limited::make_scene());
  const double unlimited = worst_overrun(spatial_arm_unlimited::make_scene());
  // The shoulder turns about the vertical, so only the forearm and hand
  // (1.10 kg) change height, their centres of mass at most 0.45 m from the
  // elbow: each drops less than 1 m, so the stops (k = 1e4, flange-urdf's
  // default) take at most E = 1.10·9.81·1 J, and no joint passes its limit
  // by more than √(2E/k) = 0.046 rad.
  const double bound = std::sqrt(2 * 1.1027 * 9.81 * 1.0 / 1e4);
  INFO("largest overrun with stops " << limited << ", without " << unlimited << ", bound " << bound);
  CHECK(limited < bound);
  CHECK(limited > 0);             // it did reach a stop
  CHECK(unlimited > 10 * bound);  // and without stops it swings through
}
