// Simulate only the effects a scene calls for: pairs of scene variants that
// differ by one effect, each variant a different type, timed per derivative
// evaluation in the same binary. After Google Benchmark's table it prints one
// line per pair, from the medians of 7 repetitions:
//
//   effect <scene> <effect>: with=<ns> without=<ns> handwritten_without=<ns>
//
// handwritten_without is the scene without the effect as a hand-written closed
// form (benchmarks/handwritten.hpp), or "-" where none is practical.
//
// Effects: gravity (World with gravity, or gravity_kind::none), damper (a
// spring-damper law on every joint axis, or none), stops (axis_law::limited
// stops at ±2 rad, the joint between them, or none), unaligned_axis (axis::any
// holding the same direction, or axis::z), rigid_body (bodies with
// rotational inertia, or point masses), spatial (the spatial algorithm forced
// on a planar scene, or the planar arithmetic its types select),
// line_spring_damper (a SpringDamper from a post to the arm's end, or none),
// dense_inertia (bodies at their links' origins declared inertia_kind::full, or
// inertia_kind::diagonal with the same diagonal J).
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <string>

#include <benchmark/benchmark.h>
#include <flange/equations_of_motion.hpp>
#include <flange/models/gimbal.hpp>

#include "handwritten.hpp"

using namespace flange;

namespace {

const models::robot_arm_params arm_p{};
const models::gantry_crane_params crane_p{};
constexpr double Mz = 0.3, f_push = 0.7, damping = 0.1;

template <class Gravity = gravity_kind::uniform, class Law = axis_law::none, class Axis = axis::z,
          class Inertia = inertia_kind::full>
auto arm() {
  auto joint = [] {
    using R = Revolute<"joint", Axis, Law>;
    if constexpr (std::is_same_v<Law, axis_law::spring_damper>) return R({.n = Vec3d::UnitZ(), .c = 0.0, .d = damping});
    else if constexpr (std::is_same_v<Law, axis_law::limited<>>)
      return R({.stop = {.lower = -2.0, .upper = 2.0, .stiffness = 1e4, .dissipation = 0.1}});
    else if constexpr (Axis::fixed) return R{};
    else return R({.n = Vec3d::UnitZ()});
  };
  auto body = [] {
    using B = Body<"mass", cm::at_frame, Inertia>;
    if constexpr (std::is_same_v<Inertia, inertia_kind::point>) return B({.m = arm_p.m});
    else return B({.m = arm_p.m, .J = Vec3d(arm_p.Jx, arm_p.Jz, arm_p.Jz).asDiagonal()});
  };
  return scene(World<"world", Gravity>{}, Torque<"motor">({.M_ext = Vec3d(0, 0, Mz)}), joint(),
               FixedTranslation<"rod">({.d = {arm_p.d, 0, 0}}), body(), connect<"world.frame_b", "joint.frame_a">,
               connect<"world.frame_b", "motor.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"joint.frame_b", "motor.frame_b">, connect<"rod.frame_b", "mass.frame_a">);
}

template <class Gravity = gravity_kind::uniform, class Law = axis_law::none, class Axis = axis::z,
          class Inertia = inertia_kind::point>
auto crane() {
  auto rail = [] {
    if constexpr (Axis::fixed) return Prismatic<"rail", axis::x>({.f = f_push});
    else return Prismatic<"rail">({.n = Vec3d::UnitX(), .f = f_push});
  };
  auto pivot = [] {
    using R = Revolute<"pivot", Axis, Law>;
    if constexpr (std::is_same_v<Law, axis_law::spring_damper>) return R({.n = Vec3d::UnitZ(), .c = 0.0, .d = damping});
    else if constexpr (Axis::fixed) return R{};
    else return R({.n = Vec3d::UnitZ()});
  };
  auto load = [] {
    using B = Body<"load", cm::at_frame, Inertia>;
    if constexpr (std::is_same_v<Inertia, inertia_kind::point>) return B({.m = crane_p.m});
    else return B({.m = crane_p.m, .J = Mat3d::Identity() * 0.01});
  };
  return scene(World<"world", Gravity>{}, rail(), Body<"cart">({.m = crane_p.M, .J = Mat3d::Identity() * 0.1 * crane_p.M}),
               pivot(), FixedTranslation<"rope">({.d = {crane_p.d, 0, 0}}), load(),
               connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
               connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rope.frame_a">,
               connect<"rope.frame_b", "load.frame_a">);
}

constexpr int NC = 6;
models::chain_params<NC> chain_p() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  models::chain_params<NC> p;
  for (int i = 0; i < NC; ++i) {
    p.axis[i] = Vec3d::UnitZ();
    p.d[i] = Vec3d(u(rng), 0.1 * u(rng), 0);
    p.m[i] = u(rng);
    p.J[i] = Vec3d(0.05, 0.06, 0.07).asDiagonal();
  }
  p.damping = damping;
  return p;
}
template <class Gravity = gravity_kind::uniform, class Law = axis_law::none, template <int> class Axes = models::planar_axes,
          class Inertia = inertia_kind::full>
auto chain6() {
  return models::chain<NC, Axes, Law, Gravity, Inertia>(chain_p());
}

/// The same scene through the spatial algorithm, whatever its type selects.
template <class S>
struct spatial {
  S s;
  template <class X>
  void operator()(const X& x, X& dx, double t) const {
    for (int i = 0; i < S::n_q; ++i) dx[i] = x[S::n_q + i];
    accelerations_newton_euler(s, t, x.data(), x.data() + S::n_q, dx.data() + S::n_q);
  }
};
template <class S>
spatial<S> forced_spatial(S s) {
  return {std::move(s)};
}

/// For instruction counts: `effects --count NAME N` evaluates one variant N
/// times inside evaluate_n, outside Google Benchmark, so that
///   valgrind --tool=callgrind --toggle-collect='*evaluate_n*' build/benchmarks/effects --count NAME 100000
/// counts its instructions alone (divide the total by N).
std::map<std::string, std::function<void(long)>> counters;
template <class System, std::size_t N>
[[gnu::noinline]] void evaluate_n(const System& sys, std::array<double, N> x, long n) {
  std::array<double, N> dx;
  for (long i = 0; i < n; ++i) {
    benchmark::DoNotOptimize(x);
    sys(x, dx, 0.0);
    benchmark::DoNotOptimize(dx);
  }
}

struct pair_names {
  std::string scene, effect;
  bool handwritten;
};
std::vector<pair_names> pairs;

/// Registers with, without and (if given) the hand-written form of `without`.
template <class With, class Without, class Handwritten, std::size_t N>
void effect(const std::string& scene, const std::string& name, With with, Without without, Handwritten hw,
            std::array<double, N> x) {
  auto reg = [&](const std::string& variant, auto sys) {
    benchmark::RegisterBenchmark((scene + "/" + name + "/" + variant).c_str(),
                                 [sys, x](benchmark::State& s) { bench::derivative(s, sys, x); })
        ->Repetitions(7)
        ->ReportAggregatesOnly(true)
        ->MinTime(0.05);
    counters[scene + "/" + name + "/" + variant] = [sys, x](long n) { evaluate_n(sys, x, n); };
  };
  reg("with", std::move(with));
  reg("without", std::move(without));
  constexpr bool has_hw = !std::is_same_v<Handwritten, std::nullptr_t>;
  if constexpr (has_hw) reg("handwritten_without", std::move(hw));
  pairs.push_back({scene, name, has_hw});
}

void register_all() {
  const std::array<double, 2> xa{0.3, 0.7};
  const bench::handwritten_arm hw_arm{arm_p, Mz};
  effect("robot_arm", "gravity", arm(), arm<gravity_kind::none>(), bench::handwritten_arm_no_gravity{arm_p, Mz}, xa);
  effect("robot_arm", "damper", arm<gravity_kind::uniform, axis_law::spring_damper>(), arm(), hw_arm, xa);
  effect("robot_arm", "unaligned_axis", arm<gravity_kind::uniform, axis_law::none, axis::any>(), arm(), hw_arm, xa);
  // Stops at ±2 rad: at xa the joint is between them, so the cost is the two comparisons.
  effect("robot_arm", "stops", arm<gravity_kind::uniform, axis_law::limited<>>(), arm(), hw_arm, xa);
  auto point_p = arm_p;
  point_p.Jz = 0;
  effect("robot_arm", "rigid_body", arm(),
         arm<gravity_kind::uniform, axis_law::none, axis::z, inertia_kind::point>(),
         bench::handwritten_arm{point_p, Mz}, xa);
  effect("robot_arm", "spatial", forced_spatial(arm()), arm(), hw_arm, xa);
  // A spring-damper from a post to the arm's end: a line force, so a position pass.
  auto sprung = scene(World<"world">{}, Torque<"motor">({.M_ext = Vec3d(0, 0, Mz)}), Revolute<"joint", axis::z>{},
                      FixedTranslation<"rod">({.d = {arm_p.d, 0, 0}}),
                      Body<"mass">({.m = arm_p.m, .J = Vec3d(arm_p.Jx, arm_p.Jz, arm_p.Jz).asDiagonal()}),
                      FixedTranslation<"post">({.d = {0.3, 0.4, 0}}), SpringDamper<"spring">({.c = 20, .s0 = 0.2, .d = 0.1}),
                      connect<"world.frame_b", "joint.frame_a">, connect<"world.frame_b", "motor.frame_a">,
                      connect<"joint.frame_b", "rod.frame_a">, connect<"joint.frame_b", "motor.frame_b">,
                      connect<"rod.frame_b", "mass.frame_a">, connect<"world.frame_b", "post.frame_a">,
                      connect<"post.frame_b", "spring.frame_a">, connect<"rod.frame_b", "spring.frame_b">);
  effect("robot_arm", "line_spring_damper", sprung, arm(), hw_arm, xa);

  const std::array<double, 4> xc{0.2, 0.4, 0.3, -0.5};
  const bench::handwritten_crane hw_crane{crane_p, f_push};
  effect("gantry_crane", "gravity", crane(), crane<gravity_kind::none>(),
         bench::handwritten_crane_no_gravity{crane_p, f_push}, xc);
  effect("gantry_crane", "damper", crane<gravity_kind::uniform, axis_law::spring_damper>(), crane(), hw_crane, xc);
  effect("gantry_crane", "unaligned_axis", crane<gravity_kind::uniform, axis_law::none, axis::any>(), crane(), hw_crane, xc);
  effect("gantry_crane", "rigid_body", crane<gravity_kind::uniform, axis_law::none, axis::z, inertia_kind::full>(),
         crane(), hw_crane, xc);
  effect("gantry_crane", "spatial", forced_spatial(crane()), crane(), hw_crane, xc);

  std::array<double, 2 * NC> x6;
  for (int i = 0; i < 2 * NC; ++i) x6[i] = 0.1 * (i + 1) * (i % 2 ? -1 : 1);
  effect("chain6", "gravity", chain6(), chain6<gravity_kind::none>(), nullptr, x6);
  effect("chain6", "damper", chain6<gravity_kind::uniform, axis_law::spring_damper>(), chain6(), nullptr, x6);
  effect("chain6", "unaligned_axis", chain6<gravity_kind::uniform, axis_law::none, models::runtime_axes>(), chain6(),
         nullptr, x6);
  effect("chain6", "rigid_body", chain6(),
         chain6<gravity_kind::uniform, axis_law::none, models::planar_axes, inertia_kind::point>(), nullptr, x6);
  effect("chain6", "spatial", forced_spatial(chain6()), chain6(), nullptr, x6);

  const std::array<double, 6> xg{0.3, -0.5, 0.8, 0.4, 0.2, -0.6};
  using inertia_kind::diagonal, inertia_kind::full, inertia_kind::point;
  effect("gimbal3", "rigid_body", models::gimbal<full, full>(), models::gimbal<full, point>(), nullptr, xg);
  effect("gimbal3", "dense_inertia", models::gimbal<full, full>(), models::gimbal<diagonal, diagonal>(), nullptr, xg);
}

struct median_reporter : benchmark::ConsoleReporter {
  std::map<std::string, double> ns;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs)
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name == "median")
        ns[r.run_name.function_name] = r.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  register_all();
  if (argc == 2 && std::string(argv[1]) == "--list") {
    for (const auto& [name, f] : counters) std::printf("%s\n", name.c_str());
    return 0;
  }
  if (argc == 4 && std::string(argv[1]) == "--count") {
    const auto c = counters.find(argv[2]);
    if (c == counters.end()) {
      std::fprintf(stderr, "effects: no variant %s\n", argv[2]);
      return 2;
    }
    c->second(std::stol(argv[3]));
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  median_reporter rep;
  benchmark::RunSpecifiedBenchmarks(&rep);
  std::printf("\n");
  for (const auto& p : pairs) {
    const std::string base = p.scene + "/" + p.effect + "/";
    const auto with = rep.ns.find(base + "with"), without = rep.ns.find(base + "without");
    if (with == rep.ns.end() || without == rep.ns.end()) continue;  // filtered out
    std::printf("effect %s %s: with=%.1f without=%.1f handwritten_without=", p.scene.c_str(), p.effect.c_str(),
                with->second, without->second);
    const auto hw = rep.ns.find(base + "handwritten_without");
    if (p.handwritten && hw != rep.ns.end()) std::printf("%.1f\n", hw->second);
    else std::printf("-\n");
  }
  return 0;
}
