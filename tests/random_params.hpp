// Deterministic random parameters and states shared by the tests.
#pragma once
#include <random>

#include <flange/models/chain.hpp>
#include <flange/models/paper.hpp>
#include <flange/models/tree.hpp>

namespace flange::test {

inline double uniform(std::mt19937& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

inline models::robot_arm_params arm_params(std::mt19937& rng) {
  const double Jz = uniform(rng, 0.01, 1.0);
  return {.m = uniform(rng, 0.1, 10), .d = uniform(rng, 0.1, 2), .Jx = uniform(rng, 0.01, 2 * Jz), .Jz = Jz,
          .g = uniform(rng, 1, 20)};
}

inline models::gantry_crane_params crane_params(std::mt19937& rng) {
  return {.M = uniform(rng, 0.1, 10), .m = uniform(rng, 0.1, 10), .d = uniform(rng, 0.1, 3), .g = uniform(rng, 1, 20)};
}

/// A random physical inertia: principal moments obeying the triangle
/// inequality, turned by a random rotation.
inline Mat3d random_inertia(std::mt19937& rng) {
  const double a = uniform(rng, 0.02, 0.1), b = uniform(rng, 0.02, 0.1), c = uniform(rng, std::abs(a - b), a + b);
  const Mat3d Q = axis_rotation<double>(Vec3d(uniform(rng, -1, 1), uniform(rng, -1, 1), 1).normalized(),
                                        uniform(rng, -3, 3));
  return Q * Vec3d(a, b, c).asDiagonal() * Q.transpose();
}

template <int N>
models::chain_params<N> chain_params(std::mt19937& rng) {
  models::chain_params<N> p;
  for (int i = 0; i < N; ++i) {
    p.axis[i] = Vec3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).normalized();
    p.d[i] = Vec3d(uniform(rng, 0.2, 1), uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3));
    p.m[i] = uniform(rng, 0.2, 2);
    p.J[i] = random_inertia(rng);
  }
  return p;
}

inline Vec3d random_vector(std::mt19937& rng, double a, double b) {
  return Vec3d(uniform(rng, a, b), uniform(rng, a, b), uniform(rng, a, b));
}

/// Random numbers for a tree of N joints: offsets of 0.2–1 m in any direction
/// (out of the plane too, for planar shapes), masses 0.2–2 kg, physical
/// inertias, laws, inputs and loads of order one.
template <int N>
models::tree_params<N> tree_params(std::mt19937& rng) {
  models::tree_params<N> p;
  for (int i = 0; i < N; ++i) {
    p.offset[i] = random_vector(rng, -1, 1).normalized() * uniform(rng, 0.2, 1);
    p.axis[i] = random_vector(rng, -1, 1).normalized();
    p.axis2[i] = random_vector(rng, -1, 1).normalized();
    p.m[i] = uniform(rng, 0.2, 2);
    p.J[i] = random_inertia(rng);
    p.r_cm[i] = random_vector(rng, -0.2, 0.2);
    p.c[i] = uniform(rng, 1, 20);
    p.d[i] = uniform(rng, 0.1, 1);
    p.q0[i] = uniform(rng, -0.5, 0.5);
    p.f_c[i] = uniform(rng, 0.1, 1);
    p.f[i] = uniform(rng, -2, 2);
    p.torque[i] = random_vector(rng, -1, 1);
    p.line_c[i] = uniform(rng, 1, 20);
    p.line_s0[i] = uniform(rng, 0.1, 0.5);
    p.line_d[i] = uniform(rng, 0.1, 1);
    p.load[i] = random_vector(rng, -2, 2);
  }
  p.g = Vec3d(uniform(rng, -1, 1), -9.81, uniform(rng, -1, 1));
  // Stops (for shapes drawn with_stops) from a stream of their own, so that
  // the numbers above stay what they were for every other test: bounds
  // inside random_state's ±1.5, so its states often press on a stop.
  static std::mt19937 stop_rng(2024);
  for (int i = 0; i < N; ++i) {
    p.lower[i] = uniform(stop_rng, -1.2, -0.2);
    p.upper[i] = uniform(stop_rng, 0.2, 1.2);
    p.k_stop[i] = uniform(stop_rng, 10, 200);
    p.d_stop[i] = uniform(stop_rng, 0, 1);
  }
  return p;
}

}  // namespace flange::test
