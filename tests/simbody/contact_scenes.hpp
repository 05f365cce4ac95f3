// The numbers of the contact scenes that contact_test.cpp and
// contact_shapes_test.cpp simulate in flange and contact_reference.cpp in
// Simbody (plain constants: they all include it).
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
// A box (a free body) thrown onto the same ground, tilted so that it lands
// on a corner, then tumbles, slides and comes to rest on a face. Its
// contact shape is its eight corners' spheres of radius corner_radius (in
// Simbody: eight Sphere surfaces on the body).
constexpr double box_m = 2.0, box_h[3] = {0.2, 0.1, 0.15}, corner_radius = 0.01;
constexpr double box_J[3] = {box_m / 3 * (box_h[1] * box_h[1] + box_h[2] * box_h[2]),
                             box_m / 3 * (box_h[0] * box_h[0] + box_h[2] * box_h[2]),
                             box_m / 3 * (box_h[0] * box_h[0] + box_h[1] * box_h[1])};
// Start: centre 0.35 m up, turned by box_angle about box_axis (unit), moving and spinning.
constexpr double box_y0 = 0.35, box_angle = 0.5, box_axis[3] = {0.6, 0.0, 0.8};
constexpr double box_v0[3] = {1.0, -0.5, 0.2}, box_w0[3] = {1.0, 2.0, -3.0};  ///< ω in body axes
}  // namespace contact_scenes
