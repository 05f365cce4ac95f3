// Per-step cost: the generated derivative against the paper's hand-written
// closed form, compiled in the same binary, for the robot arm and the gantry
// crane, called independently (throughput) and in a chain (latency); one
// runge_kutta4 step with a std::array state (array_algebra) and an Eigen
// state (vector_space_algebra), the system handed over by std::cref and by
// value; and the two algorithms (Newton–Euler +
// mass matrix, the default, against articulated-body) on chains; and the
// four-bar (a closed loop) against its hand-written one-coordinate equation
// of motion and against the same bars as an open chain.
//
// After Google Benchmark's table it prints one line per comparison,
//   ratio <scene> <what> generated/handwritten = <x.xx>
// from the medians of the repetitions, and the compile time of each example
// translation unit (measured at build time, see compile_time.cmake).
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <utility>

#include <benchmark/benchmark.h>
#include <flange/flange.hpp>
#include <flange/simulate/jacobian.hpp>

#include "handwritten.hpp"

using namespace flange;

namespace {

const models::robot_arm_params arm_p{};
const models::gantry_crane_params crane_p{};
const auto arm = models::robot_arm(arm_p, Vec3d(0, 0, 0.3));
const auto crane = models::gantry_crane(crane_p, 0.7);
const bench::handwritten_arm arm_hw{arm_p, 0.3};
const bench::handwritten_crane crane_hw{crane_p, 0.7};

/// runge_kutta4 steps, each from the state the last one reached. The system
/// goes to Odeint by std::cref, as the README says (Odeint copies its system
/// through four calls of every do_step: for a scene, its parameters and
/// folded constants); ByValue hands it over by value instead, to measure that.
template <class State, class Stepper, bool ByValue = false, class System>
void rk4_steps(benchmark::State& st, const System& sys, State x) {
  Stepper stepper;
  for (auto _ : st) {
    if constexpr (ByValue) stepper.do_step(sys, x, 0.0, 1e-4);  // small steps: the state stays near its start
    else stepper.do_step(std::cref(sys), x, 0.0, 1e-4);
    benchmark::DoNotOptimize(x);
  }
}

/// Derivatives in a chain, x ← x + h·f(x): each call waits for the one
/// before, as the four stages of a step do. bench::derivative's calls are
/// independent, so the processor overlaps them: that measures throughput,
/// this latency.
template <class System, std::size_t N>
void derivative_chained(benchmark::State& st, const System& sys, std::array<double, N> x) {
  std::array<double, N> dx;
  for (auto _ : st) {
    sys(x, dx, 0.0);
    for (std::size_t i = 0; i < N; ++i) x[i] += 1e-9 * dx[i];
    benchmark::DoNotOptimize(x);
  }
}

/// One second of a run at tolerance 1e-8: flange::simulate (checked: every
/// evaluation's state and derivative tested for finiteness, a budget
/// counted, the step size watched) against the same dopri5 steps through
/// the raw system with odeint::integrate_adaptive (the same steps: tested in
/// simulate_test). Shared: simulate's run as a target built with
/// FLANGE_SHARED_STEPS (flange_precompile_headers) makes it, its steps
/// through a type-erased system (simulate/method.hpp).
template <bool Checked, class Scene, class State, bool Shared = false>
void run_1s(benchmark::State& st, const Scene& sc, State x0) {
  for (auto _ : st) {
    State x = x0;
    if constexpr (Shared) {
      long evals = 0;
      odeint::null_observer none;
      flange::detail::observe_steps<odeint::null_observer> watch{none};
      flange::detail::checked_run<method::dopri5, true>(sc, x, 0.0, 1.0, {.tolerance = 1e-8, .dt = 1e-3}, evals,
                                                        watch);
    } else if constexpr (Checked) {
      x = simulate(sc, x, 0.0, 1.0, {.tolerance = 1e-8, .dt = 1e-3});
    } else {
      // std::cref: Odeint passes its system by value from call to call, and a
      // scene (with its precomputed model) is bigger than the checked wrapper.
      odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<State>()),
                                 std::cref(sc), x, 0.0, 1.0, 1e-3);
    }
    benchmark::DoNotOptimize(x);
  }
}

/// One evaluation of the full DAE residual F(t, y, ẏ) on a consistent point.
template <class Scene, std::size_t N>
void residual_eval(benchmark::State& st, const Scene& sc, std::array<double, N> x) {
  const auto sol = recover(sc, 0.0, x);
  auto y = sol.y;
  for (auto _ : st) {
    benchmark::DoNotOptimize(y);
    auto r = residual(sc, 0.0, y, sol.yd);
    benchmark::DoNotOptimize(r);
  }
}

/// Recovering every DAE variable (poses, velocities, cut forces, energy) from (t, x).
template <class Scene, std::size_t N>
void recover_all(benchmark::State& st, const Scene& sc, std::array<double, N> x) {
  for (auto _ : st) {
    benchmark::DoNotOptimize(x);
    auto sol = recover(sc, 0.0, x);
    benchmark::DoNotOptimize(sol);
  }
}

/// The Jacobian ∂f/∂x (with ∂f/∂t) a stiff stepper needs: exact
/// (jacobian(): analytic on trees of one-axis joints, dual numbers
/// elsewhere), or by central differences.
template <bool Exact, class Scene, std::size_t N>
void jacobian_eval(benchmark::State& st, const Scene& sc, std::array<double, N> x) {
  Eigen::Matrix<double, int(N), 1> ft;
  for (auto _ : st) {
    benchmark::DoNotOptimize(x);
    auto J = Exact ? jacobian(sc, 0.0, x, &ft) : jacobian_finite_difference(sc, 0.0, x, &ft);
    benchmark::DoNotOptimize(J);
    benchmark::DoNotOptimize(ft);
  }
}

template <int N, template <int> class Axes, bool ABA>
void chain_derivative(benchmark::State& st) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> s(-1, 1);
  const auto p = models::random_chain_params<N>(rng);
  const auto c = models::chain<N, Axes>(p);
  std::array<double, 2 * N> x, dx;
  for (auto& v : x) v = s(rng);
  for (auto _ : st) {
    benchmark::DoNotOptimize(x);
    if constexpr (ABA) {
      for (int i = 0; i < N; ++i) dx[i] = x[N + i];
      accelerations_articulated_body(c, 0.0, x.data(), x.data() + N, dx.data() + N);
    } else {
      c(x, dx, 0.0);
    }
    benchmark::DoNotOptimize(dx);
  }
}

/// The derivative of a scene at a state x (NE + mass matrix, the default, or ABA).
template <bool ABA, class Scene>
void scene_derivative(benchmark::State& st, const Scene& sc, typename Scene::state_type x) {
  typename Scene::state_type dx;
  for (auto _ : st) {
    benchmark::DoNotOptimize(x);
    if constexpr (ABA) {
      // q̇ from each joint, as the System's derivative does, then v̇ by articulated bodies
      const double* q = x.data();
      const double* v = x.data() + Scene::n_q;
      detail::joint_rates(sc, q, v, dx.data());
      accelerations_articulated_body(sc, 0.0, q, v, dx.data() + Scene::n_q);
    } else {
      sc(x, dx, 0.0);
    }
    benchmark::DoNotOptimize(dx);
  }
}

/// A free body (FreeMotion, gravity) and a floating-base robot (FreeMotion
/// trunk, four legs of three revolute joints).
const auto free_body = scene(World<"world">{}, FreeMotion<"fly">{},
                             Body<"body", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.1, 0, 0}}),
                             connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "body.frame_a">);
const auto legged = models::legged<4, 3>();
template <class S>
typename S::state_type moving_state(const S& s) {
  auto x = neutral_state(s);
  for (int i = 0; i < S::n_state; ++i) x[i] += 0.1 * std::sin(1.3 * i + 0.4);
  normalize(s, x);
  return x;
}

using A2 = std::array<double, 2>;
using A4 = std::array<double, 4>;
using E2 = Eigen::Matrix<double, 2, 1>;
using E4 = Eigen::Matrix<double, 4, 1>;
template <class S>
using rk4_array = odeint::runge_kutta4<S>;
template <class S>
using rk4_eigen = odeint::runge_kutta4<S, double, S, double, odeint::vector_space_algebra>;

const models::fourbar_params fourbar_p{};
const auto fourbar = models::fourbar(fourbar_p);
const bench::handwritten_fourbar fourbar_hw{fourbar_p};
/// The same three bars without the rocker's pivot: the tree alone, the
/// yardstick for what the loop adds.
const auto fourbar_open = [] {
  using models::bar;
  const auto& p = fourbar_p;
  return scene(World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
               Revolute<"crank_pin", axis::z>{}, bar<"coupler">(p.coupler, p.m_coupler),
               Revolute<"rocker_pin", axis::z>{}, bar<"rocker">(p.rocker, p.m_rocker),
               connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
               connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">);
}();
/// The four-bar at θ2 = 1 rad, θ̇2 = 3 rad/s, its loop closed.
std::array<double, 6> fourbar_state() {
  const auto q = models::fourbar_coordinates(fourbar_p, 1.0, models::freudenstein_rocker(fourbar_p, 1.0));
  std::array<double, 6> x{q[0], q[1], q[2], 3.0, 0, 0};
  close_loops<"crank_pivot">(fourbar, x);
  return x;
}

const A2 arm_x{0.3, 0.7};
const A4 crane_x{0.2, 0.4, 0.3, -0.5};

void register_all() {
  auto reg = [](const char* name, auto fn) {
    benchmark::RegisterBenchmark(name, fn)->Repetitions(7)->ReportAggregatesOnly(true)->MinTime(0.05);
  };
  reg("robot_arm/derivative/generated", [](benchmark::State& s) { bench::derivative(s, arm, arm_x); });
  reg("robot_arm/derivative/handwritten", [](benchmark::State& s) { bench::derivative(s, arm_hw, arm_x); });
  reg("robot_arm/rk4_step_array/generated", [](benchmark::State& s) { rk4_steps<A2, rk4_array<A2>>(s, arm, arm_x); });
  reg("robot_arm/rk4_step_array/handwritten",
      [](benchmark::State& s) { rk4_steps<A2, rk4_array<A2>>(s, arm_hw, arm_x); });
  reg("robot_arm/rk4_step_array/checked", [](benchmark::State& s) {
    static budget b;
    rk4_steps<A2, rk4_array<A2>, true>(s, checked(arm, b), arm_x);  // checked() holds a reference
  });
  reg("robot_arm/rk4_step_array/by_value", [](benchmark::State& s) { rk4_steps<A2, rk4_array<A2>, true>(s, arm, arm_x); });
  reg("gantry_crane/rk4_step_array/by_value",
      [](benchmark::State& s) { rk4_steps<A4, rk4_array<A4>, true>(s, crane, crane_x); });
  reg("robot_arm/derivative_chained/generated", [](benchmark::State& s) { derivative_chained(s, arm, arm_x); });
  reg("robot_arm/derivative_chained/handwritten", [](benchmark::State& s) { derivative_chained(s, arm_hw, arm_x); });
  reg("gantry_crane/derivative_chained/generated", [](benchmark::State& s) { derivative_chained(s, crane, crane_x); });
  reg("gantry_crane/derivative_chained/handwritten",
      [](benchmark::State& s) { derivative_chained(s, crane_hw, crane_x); });
  reg("robot_arm/simulate_1s/checked", [](benchmark::State& s) { run_1s<true>(s, arm, arm_x); });
  reg("robot_arm/simulate_1s/raw", [](benchmark::State& s) { run_1s<false>(s, arm, arm_x); });
  reg("gantry_crane/simulate_1s/checked", [](benchmark::State& s) { run_1s<true>(s, crane, crane_x); });
  reg("gantry_crane/simulate_1s/raw", [](benchmark::State& s) { run_1s<false>(s, crane, crane_x); });
  reg("robot_arm/simulate_1s/shared", [](benchmark::State& s) { run_1s<true, decltype(arm), A2, true>(s, arm, arm_x); });
  reg("gantry_crane/simulate_1s/shared",
      [](benchmark::State& s) { run_1s<true, decltype(crane), A4, true>(s, crane, crane_x); });
  reg("robot_arm/rk4_step_eigen/generated",
      [](benchmark::State& s) { rk4_steps<E2, rk4_eigen<E2>>(s, arm, E2(arm_x[0], arm_x[1])); });
  reg("robot_arm/rk4_step_eigen/handwritten",
      [](benchmark::State& s) { rk4_steps<E2, rk4_eigen<E2>>(s, arm_hw, E2(arm_x[0], arm_x[1])); });
  reg("gantry_crane/derivative/generated", [](benchmark::State& s) { bench::derivative(s, crane, crane_x); });
  reg("gantry_crane/derivative/handwritten", [](benchmark::State& s) { bench::derivative(s, crane_hw, crane_x); });
  reg("gantry_crane/rk4_step_array/generated",
      [](benchmark::State& s) { rk4_steps<A4, rk4_array<A4>>(s, crane, crane_x); });
  reg("gantry_crane/rk4_step_array/handwritten",
      [](benchmark::State& s) { rk4_steps<A4, rk4_array<A4>>(s, crane_hw, crane_x); });
  reg("gantry_crane/rk4_step_eigen/generated", [](benchmark::State& s) {
    rk4_steps<E4, rk4_eigen<E4>>(s, crane, E4(crane_x[0], crane_x[1], crane_x[2], crane_x[3]));
  });
  reg("gantry_crane/rk4_step_eigen/handwritten", [](benchmark::State& s) {
    rk4_steps<E4, rk4_eigen<E4>>(s, crane_hw, E4(crane_x[0], crane_x[1], crane_x[2], crane_x[3]));
  });
  reg("fourbar/derivative/generated", [](benchmark::State& s) { bench::derivative(s, fourbar, fourbar_state()); });
  reg("fourbar/derivative/handwritten", [](benchmark::State& s) { bench::derivative(s, fourbar_hw, A2{1.0, 3.0}); });
  reg("fourbar/derivative/open_chain", [](benchmark::State& s) { bench::derivative(s, fourbar_open, fourbar_state()); });
  reg("robot_arm/residual/106_equations", [](benchmark::State& s) { residual_eval(s, arm, arm_x); });
  reg("robot_arm/recover/all_variables", [](benchmark::State& s) { recover_all(s, arm, arm_x); });
  reg("gantry_crane/residual/125_equations", [](benchmark::State& s) { residual_eval(s, crane, crane_x); });
  reg("gantry_crane/recover/all_variables", [](benchmark::State& s) { recover_all(s, crane, crane_x); });
  reg("robot_arm/jacobian/exact", [](benchmark::State& s) { jacobian_eval<true>(s, arm, arm_x); });
  reg("robot_arm/jacobian/finite_difference", [](benchmark::State& s) { jacobian_eval<false>(s, arm, arm_x); });
  reg("gantry_crane/jacobian/exact", [](benchmark::State& s) { jacobian_eval<true>(s, crane, crane_x); });
  reg("gantry_crane/jacobian/finite_difference",
      [](benchmark::State& s) { jacobian_eval<false>(s, crane, crane_x); });
  reg("fourbar/jacobian/exact", [](benchmark::State& s) { jacobian_eval<true>(s, fourbar, fourbar_state()); });
  reg("free_body/derivative/newton_euler", [](benchmark::State& s) { scene_derivative<false>(s, free_body, moving_state(free_body)); });
  reg("free_body/derivative/articulated_body", [](benchmark::State& s) { scene_derivative<true>(s, free_body, moving_state(free_body)); });
  reg("legged/derivative/newton_euler", [](benchmark::State& s) { scene_derivative<false>(s, legged, moving_state(legged)); });
  reg("legged/derivative/articulated_body", [](benchmark::State& s) { scene_derivative<true>(s, legged, moving_state(legged)); });
  reg("chain2_planar/derivative/newton_euler", chain_derivative<2, models::planar_axes, false>);
  reg("chain2_planar/derivative/articulated_body", chain_derivative<2, models::planar_axes, true>);
  reg("chain4_spatial/derivative/newton_euler", chain_derivative<4, models::runtime_axes, false>);
  reg("chain4_spatial/derivative/articulated_body", chain_derivative<4, models::runtime_axes, true>);
  reg("chain8_spatial/derivative/newton_euler", chain_derivative<8, models::runtime_axes, false>);
  reg("chain8_spatial/derivative/articulated_body", chain_derivative<8, models::runtime_axes, true>);
}

/// Keeps the median of each benchmark's repetitions.
struct median_reporter : benchmark::ConsoleReporter {
  std::map<std::string, double> ns;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs)
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name == "median")
        ns[r.run_name.function_name] = r.GetAdjustedRealTime();  // ns per iteration
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  median_reporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  // "<tag> <scene> <what> a/b = x.xx" exactly, then the medians on their own line.
  auto ratio = [&](const char* tag, const std::string& scene, const std::string& what, const std::string& a,
                   const std::string& b) {
    const auto x = rep.ns.find(scene + "/" + what + "/" + a), y = rep.ns.find(scene + "/" + what + "/" + b);
    if (x == rep.ns.end() || y == rep.ns.end()) return;
    std::printf("%s %s %s %s/%s = %.2f\n", tag, scene.c_str(), what.c_str(), a.c_str(), b.c_str(),
                x->second / y->second);
    std::printf("  medians: %s %.1f ns, %s %.1f ns\n", a.c_str(), x->second, b.c_str(), y->second);
  };
  std::printf("\n");
  for (const char* scene : {"robot_arm", "gantry_crane", "fourbar"})
    for (const char* what : {"derivative", "derivative_chained", "rk4_step_array", "rk4_step_eigen"})
      ratio("ratio", scene, what, "generated", "handwritten");
  // A step against the four derivatives it evaluates, measured both ways:
  // "<scene> <system> rk4_step/4_derivatives = x (chained y)".
  for (const char* scene : {"robot_arm", "gantry_crane"})
    for (const char* sys : {"generated", "handwritten"}) {
      const auto at = [&](const std::string& what) { return rep.ns[std::string(scene) + "/" + what + "/" + sys]; };
      const double step = at("rk4_step_array"), d = at("derivative"), dc = at("derivative_chained");
      if (step > 0 && d > 0 && dc > 0)
        std::printf("step %s %s rk4_step/4_derivatives = %.2f (chained %.2f)\n", scene, sys, step / (4 * d),
                    step / (4 * dc));
    }
  ratio("loop", "fourbar", "derivative", "generated", "open_chain");
  for (const char* scene : {"chain2_planar", "chain4_spatial", "chain8_spatial", "free_body", "legged"})
    ratio("algorithm", scene, "derivative", "newton_euler", "articulated_body");
  ratio("overhead", "robot_arm", "rk4_step_array", "checked", "generated");
  for (const char* scene : {"robot_arm", "gantry_crane"}) ratio("overhead", scene, "rk4_step_array", "by_value", "generated");
  for (const char* scene : {"robot_arm", "gantry_crane"}) ratio("overhead", scene, "simulate_1s", "checked", "raw");
  for (const char* scene : {"robot_arm", "gantry_crane"})
    ratio("overhead", scene, "simulate_1s", "shared", "checked");
  for (const char* scene : {"robot_arm", "gantry_crane"})
    ratio("ratio", scene, "jacobian", "exact", "finite_difference");
  // (The exact Jacobian against one derivative, "jacobian <scene> N=<n> …",
  // is benchmarks/jacobian's, for these scenes and the chains.)
  for (const auto& [name, ns] : rep.ns)
    if (name.find("/residual/") != std::string::npos || name.find("/recover/") != std::string::npos)
      std::printf("cost %s = %.1f ns (median)\n", name.c_str(), ns);
#ifdef FLANGE_COMPILE_TIMES
  // Written by `cmake --build build --target compile_times`, when it was run.
  std::ifstream ct(FLANGE_COMPILE_TIMES);
  std::string line;
  if (!std::getline(ct, line))
    std::printf("compile times not measured (cmake --build build --target compile_times)\n");
  while (std::getline(ct, line)) {
    const auto comma = line.find(',');
    std::printf("compile %s %s s\n", line.substr(0, comma).c_str(), line.substr(comma + 1).c_str());
  }
#endif
  return 0;
}
