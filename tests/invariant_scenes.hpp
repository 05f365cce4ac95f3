// Scenes with invariants to keep, for the tests of the ways to integrate:
// the four-bar (a planar loop), a spatial RSUR loop (a loop with a Spherical
// joint in it), a free body tumbling about its intermediate axis (FreeMotion's
// quaternion) and a heavy top (Spherical's quaternion), each with a state to
// start from. The measures of how far a state is off its invariants are
// flange's own public ones (loop_residual) and, for quaternions, their norms.
#pragma once
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <flange/flange.hpp>

namespace invariant_scenes {
using namespace flange;

/// The four-bar with its default parameters, the crank at 6 rad/s, the loop closed.
inline auto fourbar() { return models::fourbar({}); }
using Fourbar = decltype(fourbar());
inline Fourbar::state_type fourbar_start(const Fourbar& fb) {
  const models::fourbar_params p;
  const auto q = models::fourbar_coordinates(p, 0.0, models::freudenstein_rocker(p, 0.0));
  Fourbar::state_type x{q[0], q[1], q[2], 6.0, 0, 0};
  close_loops<"crank_pivot">(fb, x);
  return x;
}

/// A spatial RSUR linkage: a crank about z, a Spherical to the coupler, a
/// Universal to the rocker, and the rocker's pivot (cut) about the axis n
/// at o4: 5 constraints on a 6-rate tree, one degree of freedom.
inline auto rsur(const Vec3d& o4, const Vec3d& n) {
  using models::bar;
  return scene(World<"world">{}, Revolute<"crank_pivot", axis::z>{}, bar<"crank">(0.2, 1.0), Spherical<"ball">{},
               bar<"coupler">(0.5, 1.0), Universal<"cardan">({.n_a = {0, 0, 1}, .n_b = {0, 1, 0}}),
               bar<"rocker">(0.4, 1.0), FixedTranslation<"ground">({.d = o4}), Revolute<"rocker_pivot">({.n = n}),
               connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "ball.frame_a">, connect<"ball.frame_b", "coupler.frame_a">,
               connect<"coupler.frame_b", "cardan.frame_a">, connect<"cardan.frame_b", "rocker.frame_a">,
               connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "rocker_pivot.frame_a">,
               connect<"rocker.frame_b", "rocker_pivot.frame_b">);
}
using Rsur = decltype(rsur(Vec3d::UnitX(), Vec3d::UnitY()));
/// The RSUR's state at which the open chain is placed: the pivot is put where
/// the chain's end is, about the axis of the rocker's rotation there, so this
/// state closes the loop, generically away from singular positions.
inline Rsur::state_type rsur_chain_state(const Rsur& probe) {
  return initial_state<"crank_pivot", "ball", "cardan">(
      probe, {.q = 0.5, .v = 3.0}, {.R = orientation::axis_angle({0.3, 0.2, 1.0}, -0.9)}, {.q = {0.7, -0.4}});
}
/// The closed RSUR and its state (the rates made consistent with the loop).
struct closed_rsur {
  Rsur scene;
  Rsur::state_type x;
};
inline closed_rsur rsur_closed() {
  const auto probe = rsur(Vec3d::UnitX(), Vec3d::UnitY());
  auto x = rsur_chain_state(probe);
  const auto& end = recover(probe, 0.0, x).frame("rocker.frame_b");
  const Eigen::AngleAxisd turn(Mat3d(end.R.transpose()));
  closed_rsur c{rsur(end.r, turn.axis()), x};
  close_loops<"crank_pivot">(c.scene, c.x);
  return c;
}

/// A free box tumbling about its intermediate axis, no gravity.
inline auto free_body() {
  return scene(World<"world", gravity_kind::none>{}, FreeMotion<"fly">{},
               Body<"box">({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal()}),
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "box.frame_a">);
}
using FreeBody = decltype(free_body());
inline FreeBody::state_type free_body_start(const FreeBody& s) {
  return initial_state<"fly">(s, {.r = {0, 0, 0}, .v = {0.1, 0, 0}, .R = orientation::axis_angle({1, 2, 3}, 0.4),
                                  .w = {0.01, 4.0, 0.01}});
}

/// A heavy symmetric top on a ball joint, released tilted and spinning.
inline auto top() {
  return scene(World<"world">({.g = {0, -9.81, 0}}), Spherical<"pivot">{},
               Body<"top", cm::offset>({.m = 0.5, .J = Vec3d(2e-4, 3e-4, 2e-4).asDiagonal(), .r_cm = {0, 0.04, 0}}),
               connect<"world.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "top.frame_a">);
}
using Top = decltype(top());
inline Top::state_type top_start(const Top& s) {
  auto x = neutral_state(s);
  set_joint<"pivot">(s, x, {.R = orientation::axis_angle(Vec3d::UnitZ(), 0.5), .w = Vec3d(0, 120, 0)});
  return x;
}

/// |‖q‖ − 1| of the quaternion stored at x[at … at + 3].
template <class X>
double quaternion_error(const X& x, int at) {
  double s = 0;
  for (int i = 0; i < 4; ++i) s += x[at + i] * x[at + i];
  return std::abs(std::sqrt(s) - 1);
}

}  // namespace invariant_scenes
