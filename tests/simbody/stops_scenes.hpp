// The numbers of the joint-stop scenes that stops_test.cpp simulates in
// flange and stops_reference.cpp in Simbody (plain constants: both include it).
#pragma once

namespace stops_scenes {
constexpr double g = 9.81;
constexpr double m = 1.5, L = 0.6;
constexpr double J[3] = {0.01, 0.02, 0.03};  ///< central inertia
// The pendulum starts level (q = 0) and falls onto its lower stop.
constexpr double pin_k = 300, pin_d = 0.4, pin_lower = -0.4, pin_upper = 1.0;
constexpr double pin_q0 = 0, pin_u0 = 0.5;
// The block slides along x (no gravity along it) and bounces between its stops.
constexpr double slider_k = 2000, slider_d = 0.2, slider_lower = -0.25, slider_upper = 0.3;
constexpr double slider_q0 = 0, slider_u0 = 1.2;
constexpr int samples = 300;
constexpr double dt = 0.01;
}  // namespace stops_scenes
