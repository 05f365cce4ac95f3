// The 3-joint spatial arm of docs/tutorial.md, shared by examples/spatial_arm.cpp
// (which simulates it) and examples/urdf_arm.cpp (which compares the same arm
// read from a URDF file with it): a steel box and two aluminium tubes whose
// mass and inertia flange computes from their shapes, each joint driven by a
// PD law that reads its joint by name. Seven components, six connections.
#pragma once
#include <string_view>

#include <flange/flange.hpp>

namespace spatial_arm {

/// A joint's PD law: target angle [rad], gains kp [N m/rad] and kd [N m s/rad].
struct pd_gains {
  double target, kp, kd;
};
/// The gains of each joint, by name (the URDF arm picks them the same way).
constexpr pd_gains gains(std::string_view joint) {
  return joint == "shoulder" ? pd_gains{1.0, 60, 12} : joint == "elbow" ? pd_gains{-0.8, 150, 20} : pd_gains{0.4, 20, 2};
}

/// The PD torque for the joint named Name: kp·(target − q) − kd·q̇.
template <flange::fixed_string Name>
inline auto pd = [](auto, const auto& x) {
  constexpr pd_gains g = gains(Name.view());
  return g.kp * (g.target - flange::q<Name>(x)) - g.kd * flange::v<Name>(x);
};

inline auto make_scene() {
  using namespace flange;
  return scene(
      World<"world">({.g = {0, 0, -9.81}}),  //
      revolute<"shoulder", axis::z>(pd<"shoulder">), revolute<"elbow", axis::y>(pd<"elbow">),
      revolute<"wrist", axis::y>(pd<"wrist">),  //
      BodyBox<"upper">({.r = {0.5, 0, 0}, .width = 0.06, .height = 0.04}),
      BodyCylinder<"fore">({.r = {0.4, 0, 0}, .diameter = 0.05, .inner_diameter = 0.04, .density = 2700}),
      BodyCylinder<"hand">({.r = {0.1, 0, 0}, .diameter = 0.04, .density = 2700}),
      connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
      connect<"upper.frame_b", "elbow.frame_a">, connect<"elbow.frame_b", "fore.frame_a">,
      connect<"fore.frame_b", "wrist.frame_a">, connect<"wrist.frame_b", "hand.frame_a">);
}

}  // namespace spatial_arm
