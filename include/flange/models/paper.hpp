// The two scenes of seed-paper.md, and the equations of motion the paper
// derives for them by hand.
//
// Robot arm (Figure 2): World, Torque, Revolute (axis z), FixedTranslation
// (d along x), Body. The joint angle φ is zero with the arm horizontal; the
// paper's θ = φ + π/2 is measured from the downward vertical:
//
//     (J_z + m·d²)·θ̈ + m·d·g·sin θ = M_z
//
// Gantry crane (Figure 3): World, Prismatic (axis x, force f), cart Body,
// Revolute (axis z), FixedTranslation (d along x), load Body (a point mass):
//
//     s̈ = (f + (g·cos θ + d·θ̇²)·m·sin θ) / (M + m·sin²θ)
//     θ̈ = −(f·cos θ + M·g·sin θ + (g + d·θ̇²·cos θ)·m·sin θ) / (d·(M + m·sin²θ))
#pragma once
#include <cmath>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/torque.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

struct robot_arm_params {
  double m = 1.0;    ///< mass of the arm's body [kg]
  double d = 0.5;    ///< joint to body [m]
  double Jx = 0.01;  ///< body inertia about its x axis [kg m²]
  double Jz = 0.02;  ///< body inertia about y and z [kg m²]
  double g = 9.81;   ///< gravity [m/s²], pointing along −y
};

/// The paper's robot arm. M_ext is a constant torque vector, a callable of t,
/// or of (t, x) with x the joint state (φ = x.q(0), φ̇ = x.v(0)).
template <class In = Vec3d>
auto robot_arm(const robot_arm_params& p = {}, In M_ext = Vec3d::Zero()) {
  return scene(World<"world">({.g = {0, -p.g, 0}}),                //
               torque<"motor">(std::move(M_ext)),                   //
               Revolute<"joint", axis::z>{},                        //
               FixedTranslation<"rod">({.d = {p.d, 0, 0}}),         //
               Body<"mass">({.m = p.m, .J = Vec3d(p.Jx, p.Jz, p.Jz).asDiagonal()}),
               connect<"world.frame_b", "joint.frame_a">,           //
               connect<"world.frame_b", "motor.frame_a">,           //
               connect<"joint.frame_b", "rod.frame_a">,             //
               connect<"joint.frame_b", "motor.frame_b">,           //
               connect<"rod.frame_b", "mass.frame_a">);
}

/// θ̈ of the paper's closed form, θ = φ + π/2.
inline double robot_arm_theta_dd(const robot_arm_params& p, double Mz, double theta) {
  return (Mz - p.m * p.d * p.g * std::sin(theta)) / (p.Jz + p.m * p.d * p.d);
}

struct gantry_crane_params {
  double M = 1.0;   ///< cart mass [kg]
  double m = 0.5;   ///< load mass (a point mass) [kg]
  double d = 1.0;   ///< rope length [m]
  double g = 9.81;  ///< gravity [m/s²], along −y
};

/// The paper's gantry crane. f is a constant, a callable of t, or of (t, x)
/// with x = (s, φ; ṡ, φ̇).
template <class Force = double>
auto gantry_crane(const gantry_crane_params& p = {}, Force f = 0.0) {
  return scene(World<"world">({.g = {0, -p.g, 0}}),                          //
               Prismatic<"rail", axis::x, Force>({.f = std::move(f)}),        //
               Body<"cart">({.m = p.M, .J = Mat3d::Identity() * 0.1 * p.M}),  //
               Revolute<"pivot", axis::z>{},                                  //
               FixedTranslation<"rope">({.d = {p.d, 0, 0}}),                  //
               Body<"load">({.m = p.m}),                                      //
               connect<"world.frame_b", "rail.frame_a">,                      //
               connect<"rail.frame_b", "cart.frame_a">,                       //
               connect<"rail.frame_b", "pivot.frame_a">,                      //
               connect<"pivot.frame_b", "rope.frame_a">,                      //
               connect<"rope.frame_b", "load.frame_a">);
}

/// (s̈, θ̈) of the paper's standard form.
struct crane_accelerations {
  double s_dd, theta_dd;
};
inline crane_accelerations gantry_crane_accelerations(const gantry_crane_params& p, double f, double theta,
                                                      double theta_d) {
  const double s = std::sin(theta), c = std::cos(theta);
  const double den = p.M + p.m * s * s;
  return {(f + (p.g * c + p.d * theta_d * theta_d) * p.m * s) / den,
          -(f * c + p.M * p.g * s + (p.g + p.d * theta_d * theta_d * c) * p.m * s) / (p.d * den)};
}

}  // namespace flange::models
