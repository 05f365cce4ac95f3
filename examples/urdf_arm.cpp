// The spatial arm of examples/spatial_arm.cpp, read from a URDF file
// (examples/urdf/spatial_arm.urdf) by flange-urdf at build time
// (flange_urdf_scene in examples/CMakeLists.txt), driven by one PD law
// shared by its three joints, and checked against the hand-written arm: the
// same physics, so the same motion.
//
//   urdf_arm                  simulate 4 s and compare with the hand-written scene
//   urdf_arm --equations      print the generated scene's equations
#include <cmath>
#include <cstring>
#include <iostream>

#include <flange/flange.hpp>

#include "spatial_arm.hpp"       // the hand-written arm and its gains
#include "spatial_arm_urdf.hpp"  // generated: spatial_arm_urdf::make_scene()

using namespace flange;

int main(int argc, char** argv) {
  bool equations = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--equations")) equations = true;
    else return std::cerr << "usage: urdf_arm [--equations]\n", 2;
  }

  // One PD law for every joint; the joint's name picks its target and gains
  // (the same gains as the hand-written arm's, examples/spatial_arm.hpp).
  auto pd = [](auto joint, auto, const auto& x) {
    constexpr auto name = decltype(joint)::name;
    constexpr spatial_arm::pd_gains g = spatial_arm::gains(name.view());
    return g.kp * (g.target - q<name>(x)) - g.kd * v<name>(x);
  };
  const auto arm = spatial_arm_urdf::make_scene(pd);
  using Arm = decltype(arm);
  if (equations) {
    print_equations(arm, std::cout);
    return 0;
  }

  // The hand-written arm (examples/spatial_arm.hpp), for comparison.
  const auto by_hand = spatial_arm::make_scene();

  auto x = initial_state<"elbow">(arm, {.q = 0.6});
  auto y = initial_state<"elbow">(by_hand, {.q = 0.6});
  budget bx{.max_rhs_evals = 1'000'000}, by{.max_rhs_evals = 1'000'000};
  auto stepper = [] { return odeint::make_controlled(1e-11, 1e-11, odeint::runge_kutta_dopri5<Arm::state_type>()); };
  odeint::integrate_adaptive(stepper(), checked(arm, bx), x, 0.0, 4.0, 1e-3);
  odeint::integrate_adaptive(stepper(), checked(by_hand, by), y, 0.0, 4.0, 1e-3);
  double diff = 0;
  for (int i = 0; i < Arm::n_state; ++i) diff = std::max(diff, std::abs(x[i] - y[i]));

  std::cout << "flange URDF arm: " << Arm::n_equations << " equations, " << Arm::n_unknowns
            << " unknowns, from examples/urdf/spatial_arm.urdf (3 joints, one shared PD drive)\n"
            << "  after 4 s: shoulder " << x[0] << ", elbow " << x[1] << ", wrist " << x[2] << " rad\n"
            << "  largest difference from the hand-written arm with BodyBox/BodyCylinder links: " << diff
            << (diff <= 1e-8 ? " (agree)" : " (DISAGREE)") << "\n"
            << "  largest scaled residual at the end " << scaled_residual(arm, recover(arm, 4.0, x)) << "\n";
  return diff <= 1e-8 ? 0 : 1;
}
