// The small scenes of the Jacobian benchmark (benchmarks/jacobian/), built
// as the benchmark builds them, with their jacobian() or their derivative
// called K times at a state that moves by ±1e-12 each call, for callgrind's
// instruction counts. Not part of the CMake build: tools/jacobian_counts.sh
// compiles it and prints one line per scene.
//
//   probe <scene> <K> [d]     scene: chain_any_1, chain_typed_2, gantry_crane,
//                             spatial_arm, free_body, tree_legged_1, tree_legged_2,
//                             tree_legged_4, fourbar
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>
#include <flange/models/paper.hpp>
#include <flange/simulate/jacobian.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "../../benchmarks/jacobian/states.hpp"
#include "../../examples/spatial_arm.hpp"

namespace {
double sink = 0;

/// K calls of jacobian() (or of the derivative) of scene s from state x.
template <class Scene, class State>
void calls(const Scene& s, State x, long k, bool derivative) {
  using S = std::remove_cvref_t<Scene>;
  flange::jacobian_matrix<S> J;
  typename S::state_type f;
  double step = 1e-12;
  for (long i = 0; i < k; ++i) {
    if (derivative) {
      s(x, f, 0.0);
      sink += f[S::n_state - 1];
    } else {
      flange::jacobian(s, 0.0, x, J);
      sink += J(S::n_state - 1, 0);
    }
    x[0] += step;  // a new state each call
    step = -step;
    asm volatile("" : : "r"(x.data()) : "memory");
  }
}

/// A scene of benchmarks/jacobian/states.hpp at its state.
template <class SceneAndState>
void calls(const SceneAndState& p, long k, bool derivative) {
  calls(p.first, p.second, k, derivative);
}
}  // namespace

int main(int argc, char** argv) {
  using namespace flange;
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s <scene> <K> [d]\n", argv[0]);
    return 2;
  }
  const std::string_view scene = argv[1];
  const long k = std::atol(argv[2]);
  const bool d = argc > 3;
  if (scene == "chain_any_1") {
    calls(jacobian_bench::random_chain<1, models::runtime_axes>(), k, d);
  } else if (scene == "chain_typed_2") {
    calls(jacobian_bench::random_chain<2, jacobian_bench::xyz_axes>(), k, d);
  } else if (scene == "gantry_crane") {
    calls(models::gantry_crane({}, 0.5), std::array<double, 4>{0.2, 0.4, 0.3, -0.5}, k, d);
  } else if (scene == "spatial_arm") {
    const auto arm = spatial_arm::make_scene();
    calls(arm, initial_state<"elbow">(arm, {.q = 0.6, .v = 0.4}), k, d);
  } else if (scene == "free_body") {
    const auto body = flange::scene(
        World<"world">{}, FreeMotion<"fly">{},
        Body<"b", cm::offset>({.m = 1, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.1, 0, 0}}),
        connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">);
    calls(body, std::array<double, 13>{0, 0.099, 0, 0, 0, 0, 1, 0.5, -0.1, 0.2, 1.0, 2.0, -3.0}, k, d);
  } else if (scene == "tree_legged_1") {
    calls(jacobian_bench::legged_tree<1, 1>(), k, d);
  } else if (scene == "tree_legged_2") {
    calls(jacobian_bench::legged_tree<2, 1>(), k, d);
  } else if (scene == "tree_legged_4") {
    calls(jacobian_bench::legged_tree<4, 1>(), k, d);
  } else if (scene == "fourbar") {
    const models::fourbar_params p{};
    const auto fb = models::fourbar(p);
    const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
    std::array<double, 6> x{q[0], q[1], q[2], 3.0, 0, 0};
    close_loops<"crank_pivot">(fb, x);
    calls(fb, x, k, d);
  } else {
    std::fprintf(stderr, "unknown scene %s\n", argv[1]);
    return 2;
  }
  if (sink == 0.123) std::printf("\n");
}
