// What contact costs per derivative: the same scene with and without its
// Contact pairs, at a state where every pair touches and slips (so each
// pair computes its whole law), timed in turns in one process. Prints
//   contact <scene> pairs=<n> with_ns=<x> without_ns=<y>
// from the medians of 7 repetitions: a ball on the ground (a free body, one
// pair) and the quadruped of models/legged.hpp on its four feet.
//
//   build/benchmarks/contact [calls per repetition, default 200000]
//   build/benchmarks/contact --count <ball|legged> <with|without> <n>
//       n derivatives of one scene and nothing else: under
//       valgrind --tool=callgrind, the instructions of 2000 calls less those
//       of 1000, over 1000, are one derivative's (docs/contact.md's table)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <flange/flange.hpp>
#include <flange/models/ball.hpp>
#include <flange/models/legged.hpp>

using namespace flange;

namespace {

/// Nanoseconds per derivative over n calls, each from the last one's state
/// nudged by its rate (so that calls cannot be merged or hoisted).
template <class S>
double ns_per_call(const S& s, typename S::state_type x, long n) {
  typename S::state_type dx{};
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < n; ++k) {
    s(x, dx, 0.0);
    x[x.size() - 1] += 1e-12 * dx[x.size() - 1];
  }
  const auto t1 = std::chrono::steady_clock::now();
  volatile double sink = x[0] + dx[0];
  (void)sink;
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / double(n);
}

template <class With, class Without>
void compare(const char* name, int pairs, const With& with, const typename With::state_type& xw,
             const Without& without, const typename Without::state_type& xo, long n) {
  std::vector<double> a, b;
  for (int r = 0; r < 7; ++r) {  // in turns, so that the machine's drift falls on both
    a.push_back(ns_per_call(with, xw, n));
    b.push_back(ns_per_call(without, xo, n));
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::printf("contact %s pairs=%d with_ns=%.1f without_ns=%.1f\n", name, pairs, a[3], b[3]);
}

}  // namespace

int main(int argc, char** argv) {
  // --count <ball|legged> <with|without> <n>: only n derivatives of one
  // scene, for callgrind's instruction counts (the difference of two n).
  const bool count = argc == 5 && std::string(argv[1]) == "--count";
  const std::string which = count ? argv[2] : "", variant = count ? argv[3] : "";
  const long n = count ? std::atol(argv[4]) : argc > 1 ? std::atol(argv[1]) : 200000;
  auto run = [&](const char* name, int pairs, const auto& with, const auto& xw, const auto& without, const auto& xo,
                 long calls) {
    if (!count) return compare(name, pairs, with, xw, without, xo, calls);
    if (which != name) return;
    volatile double sink = variant == "with" ? ns_per_call(with, xw, n) : ns_per_call(without, xo, n);
    (void)sink;
  };
  {
    const auto with = models::ball_on_ground();
    const auto without = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"ball">({.m = 1.0, .J = Mat3d::Identity() * 0.004}),
                               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "ball.frame_a">);
    // 1 mm into the ground, sliding and spinning.
    decltype(with)::state_type x{0, 0.099, 0, 0, 0, 0, 1, 0.5, -0.1, 0.2, 1.0, 2.0, -3.0};
    run("ball", 1, with, x, without, x, n);
  }
  {
    const auto with = models::legged<4, 3, true>();
    const auto without = models::legged<4, 3, false>();
    // Legs straight down, the trunk 2 mm low: every foot 2 mm into the ground, moving.
    using X = decltype(with)::state_type;
    X x{};
    x[1] = -0.002;
    x[6] = 1;
    for (int i = 19; i < int(x.size()); ++i) x[i] = 0.01 * (i % 5) - 0.02;
    run("legged", 4, with, x, without, x, n / 4);
  }
}
