// The paper's hand-derived equations of motion as Odeint systems: the
// references every generated derivative is measured against (with and
// without gravity), and the loop that times one evaluation.
#pragma once
#include <array>
#include <cmath>

#include <benchmark/benchmark.h>
#include <flange/models/linkages.hpp>
#include <flange/models/paper.hpp>

namespace flange::bench {

/// (J_z + m d²)·θ̈ + m·d·g·sin θ = M_z, with x = (θ, θ̇).
struct handwritten_arm {
  models::robot_arm_params p;
  double Mz;
  template <class State>
  void operator()(const State& x, State& dx, double) const {
    dx[0] = x[1];
    dx[1] = (Mz - p.m * p.d * p.g * std::sin(x[0])) / (p.Jz + p.m * p.d * p.d);
  }
};

/// The crane's standard form, with x = (s, θ, ṡ, θ̇).
struct handwritten_crane {
  models::gantry_crane_params p;
  double f;
  template <class State>
  void operator()(const State& x, State& dx, double) const {
    const double s = std::sin(x[1]), c = std::cos(x[1]), w2 = x[3] * x[3];
    const double den = p.M + p.m * s * s;
    dx[0] = x[2];
    dx[1] = x[3];
    dx[2] = (f + (p.g * c + p.d * w2) * p.m * s) / den;
    dx[3] = -(f * c + p.M * p.g * s + (p.g + p.d * w2 * c) * p.m * s) / (p.d * den);
  }
};

/// The arm without gravity: θ̈ = M_z / (J_z + m·d²).
struct handwritten_arm_no_gravity {
  models::robot_arm_params p;
  double Mz;
  template <class State>
  void operator()(const State& x, State& dx, double) const {
    dx[0] = x[1];
    dx[1] = Mz / (p.Jz + p.m * p.d * p.d);
  }
};

/// The crane's standard form with g = 0, simplified by hand.
struct handwritten_crane_no_gravity {
  models::gantry_crane_params p;
  double f;
  template <class State>
  void operator()(const State& x, State& dx, double) const {
    const double s = std::sin(x[1]), c = std::cos(x[1]), w2 = x[3] * x[3];
    const double den = p.M + p.m * s * s, pull = p.d * w2 * p.m * s;
    dx[0] = x[2];
    dx[1] = x[3];
    dx[2] = (f + pull) / den;
    dx[3] = -(f + pull) * c / (p.d * den);
  }
};

/// The free four-bar in its one coordinate θ2, by Lagrange with the loop
/// closed in closed form (models::fourbar_crank_acceleration): what one would
/// write by hand for this mechanism.
struct handwritten_fourbar {
  models::fourbar_params p;
  template <class State>
  void operator()(const State& x, State& dx, double) const {
    dx[0] = x[1];
    dx[1] = models::fourbar_crank_acceleration(p, x[0], x[1]);
  }
};

/// One derivative evaluation per iteration, inputs and outputs kept opaque.
template <class System, std::size_t N>
void derivative(benchmark::State& st, const System& sys, std::array<double, N> x) {
  std::array<double, N> dx;
  for (auto _ : st) {
    benchmark::DoNotOptimize(x);
    sys(x, dx, 0.0);
    benchmark::DoNotOptimize(dx);
  }
}

}  // namespace flange::bench
