// One side of tools/ab_derivative.sh: the paper's arm and crane, generated and
// hand-written, each behind a function of its own. The script compiles this
// file twice, once against another commit's headers and once against this
// tree's, with the namespace renamed (-Dflange=...) and AB_SIDE naming the
// functions, so that both versions live in one program and are timed in turns.
// Not part of the CMake build.
#include <flange/flange.hpp>

#include "handwritten.hpp"

#define AB_CAT_(a, b) a##b
#define AB_CAT(a, b) AB_CAT_(a, b)
#define AB_FN(name) AB_CAT(AB_CAT(name, _), AB_SIDE)

using ab_state = std::array<double, 4>;

namespace {
const flange::models::robot_arm_params arm_p{};
const flange::models::gantry_crane_params crane_p{};
const auto arm = flange::models::robot_arm(arm_p, flange::Vec3d(0, 0, 0.3));
const auto crane = flange::models::gantry_crane(crane_p, 0.7);
const flange::bench::handwritten_arm arm_hw{arm_p, 0.3};
const flange::bench::handwritten_crane crane_hw{crane_p, 0.7};

/// A scene with a state of two (q, v) on the first two entries of ab_state.
template <class System>
void on_first_two(const System& sys, const ab_state& x, ab_state& dx) {
  const std::array<double, 2> x2{x[0], x[1]};
  std::array<double, 2> d2;
  sys(x2, d2, 0.0);
  dx[0] = d2[0];
  dx[1] = d2[1];
}
}  // namespace

// The arm's state is (q, v): it uses x[0], x[1] and writes dx[0], dx[1].
[[gnu::noinline]] void AB_FN(arm)(const ab_state& x, ab_state& dx) { on_first_two(arm, x, dx); }
[[gnu::noinline]] void AB_FN(arm_handwritten)(const ab_state& x, ab_state& dx) { on_first_two(arm_hw, x, dx); }
[[gnu::noinline]] void AB_FN(crane)(const ab_state& x, ab_state& dx) { crane(x, dx, 0.0); }
[[gnu::noinline]] void AB_FN(crane_handwritten)(const ab_state& x, ab_state& dx) { crane_hw(x, dx, 0.0); }
