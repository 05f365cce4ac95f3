// The numbers of the contact scenes that contact_test.cpp simulates in
// flange and contact_reference.cpp in Simbody (plain constants: both include it).
#pragma once

namespace contact_scenes {
constexpr double g = 9.81;
// A ball (a free body) thrown onto the ground (the half-space y ≤ 0): it
// bounces, slides with spin, and rolls.
constexpr double m = 1.0, radius = 0.1;
constexpr double J[3] = {0.004, 0.004, 0.004};  ///< central inertia (a solid sphere: 2/5·m·r²)
constexpr double stiffness = 1e7, dissipation = 0.5;
constexpr double static_friction = 0.8, dynamic_friction = 0.6, viscous_friction = 0.02;
constexpr double transition_velocity = 0.05;
// Start: centre 0.25 m up, moving along x and toward the ground, spinning about z and x.
constexpr double y0 = 0.25, vx0 = 1.5, vy0 = -0.5, vz0 = 0.3, wx0 = 4.0, wz0 = -8.0;
constexpr int samples = 150;
constexpr double dt = 0.01;
}  // namespace contact_scenes
