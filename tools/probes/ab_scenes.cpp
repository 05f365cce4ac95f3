// One side of tools/ab_derivative.sh: the paper's arm and crane and the
// four-bar (a loop), generated and hand-written, each behind a function of its own. The script compiles this
// file twice, once against another commit's headers and once against this
// tree's, with the namespace renamed (-Dflange=...) and AB_SIDE naming the
// functions, so that both versions live in one program and are timed in turns.
// Not part of the CMake build.
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

#include "handwritten.hpp"

#define AB_CAT_(a, b) a##b
#define AB_CAT(a, b) AB_CAT_(a, b)
#define AB_FN(name) AB_CAT(AB_CAT(name, _), AB_SIDE)

using ab_state = std::array<double, 6>;

namespace {
const flange::models::robot_arm_params arm_p{};
const flange::models::gantry_crane_params crane_p{};
const auto arm = flange::models::robot_arm(arm_p, flange::Vec3d(0, 0, 0.3));
const auto crane = flange::models::gantry_crane(crane_p, 0.7);
const flange::bench::handwritten_arm arm_hw{arm_p, 0.3};
const flange::bench::handwritten_crane crane_hw{crane_p, 0.7};
const flange::models::fourbar_params fourbar_p{};
const auto fourbar = flange::models::fourbar(fourbar_p);
const flange::bench::handwritten_fourbar fourbar_hw{fourbar_p};
/// The four-bar at θ2 = 1 rad, θ̇2 = 3 rad/s, its loop closed (step_cost's state).
const std::array<double, 6> fourbar_x = [] {
  const auto q = flange::models::fourbar_coordinates(fourbar_p, 1.0, flange::models::freudenstein_rocker(fourbar_p, 1.0));
  std::array<double, 6> x{q[0], q[1], q[2], 3.0, 0, 0};
  flange::close_loops<"crank_pivot">(fourbar, x);
  return x;
}();

/// A scene with a state of two (q, v) on the first two entries of ab_state.
template <class System>
void on_first_two(const System& sys, const ab_state& x, ab_state& dx) {
  const std::array<double, 2> x2{x[0], x[1]};
  std::array<double, 2> d2;
  sys(x2, d2, 0.0);
  dx[0] = d2[0];
  dx[1] = d2[1];
}
/// A scene with a state of four on the first four entries of ab_state.
template <class System>
void on_first_four(const System& sys, const ab_state& x, ab_state& dx) {
  const std::array<double, 4> x4{x[0], x[1], x[2], x[3]};
  std::array<double, 4> d4;
  sys(x4, d4, 0.0);
  for (int i = 0; i < 4; ++i) dx[i] = d4[i];
}
/// The four-bar at its own state, made to depend on x[1] (the driver keeps
/// x[1] − 0.7 at zero): its rate θ̇2 is written in dx[1].
template <class System>
void fourbar_at(const System& sys, const ab_state& x, ab_state& dx) {
  std::array<double, 6> xs = fourbar_x, d;
  xs[3] += x[1] - 0.7;
  sys(xs, d, 0.0);
  dx[1] = d[3];
}
/// The hand-written four-bar in its one coordinate and rate.
template <class System>
void fourbar_hw_at(const System& sys, const ab_state& x, ab_state& dx) {
  const std::array<double, 2> xs{fourbar_x[0], fourbar_x[3] + x[1] - 0.7};
  std::array<double, 2> d;
  sys(xs, d, 0.0);
  dx[1] = d[1];
}
}  // namespace

// The arm's state is (q, v): it uses x[0], x[1] and writes dx[0], dx[1].
[[gnu::noinline]] void AB_FN(arm)(const ab_state& x, ab_state& dx) { on_first_two(arm, x, dx); }
[[gnu::noinline]] void AB_FN(arm_handwritten)(const ab_state& x, ab_state& dx) { on_first_two(arm_hw, x, dx); }
[[gnu::noinline]] void AB_FN(crane)(const ab_state& x, ab_state& dx) { on_first_four(crane, x, dx); }
[[gnu::noinline]] void AB_FN(crane_handwritten)(const ab_state& x, ab_state& dx) { on_first_four(crane_hw, x, dx); }
[[gnu::noinline]] void AB_FN(fourbar)(const ab_state& x, ab_state& dx) { fourbar_at(fourbar, x, dx); }
[[gnu::noinline]] void AB_FN(fourbar_handwritten)(const ab_state& x, ab_state& dx) { fourbar_hw_at(fourbar_hw, x, dx); }
