// The timing side of tools/ab_derivative.sh: each derivative of
// tools/probes/ab_scenes.cpp from the other commit (side a) and from this tree
// (side b), timed in turns, 41 rounds of 4·10⁵ calls each, in two loops:
// throughput (the calls independent) and latency (each call's state depends
// on the previous call's result). Not part of the CMake build.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <vector>

using ab_state = std::array<double, 6>;
using fn = void (*)(const ab_state&, ab_state&);
#define AB_DECLARE(name) \
  void name##_a(const ab_state&, ab_state&); \
  void name##_b(const ab_state&, ab_state&);
AB_DECLARE(arm)
AB_DECLARE(arm_handwritten)
AB_DECLARE(crane)
AB_DECLARE(crane_handwritten)
AB_DECLARE(fourbar)
AB_DECLARE(fourbar_handwritten)

namespace {
template <class T>
inline void opaque(T& v) { asm volatile("" : "+m"(v) : : "memory"); }

double ns_per_call(fn f, long k, bool latency) {
  ab_state x{0.3, 0.7, 0.3, -0.5, 0, 0}, dx{};
  const auto t0 = std::chrono::steady_clock::now();
  for (long i = 0; i < k; ++i) {
    opaque(x);
    f(x, dx);
    opaque(dx);
    if (latency) {  // the next state waits for this result; the value stays the same
      x[1] = 0.7 + 1e-300 * dx[1];
      x[3] = -0.5 + 1e-300 * dx[3];
    }
  }
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / double(k);
}
}  // namespace

int main() {
  struct scene { const char* name; fn a, b; };
  const scene scenes[] = {{"robot_arm", arm_a, arm_b},
                          {"robot_arm_handwritten", arm_handwritten_a, arm_handwritten_b},
                          {"gantry_crane", crane_a, crane_b},
                          {"gantry_crane_handwritten", crane_handwritten_a, crane_handwritten_b},
                          {"fourbar", fourbar_a, fourbar_b},
                          {"fourbar_handwritten", fourbar_handwritten_a, fourbar_handwritten_b}};
  constexpr int n_scenes = sizeof(scenes) / sizeof(scenes[0]);
  constexpr int rounds = 41;
  for (const bool latency : {false, true}) {
    std::vector<double> ta[n_scenes], tb[n_scenes];
    for (int r = 0; r < rounds; ++r)
      for (int i = 0; i < n_scenes; ++i) {
        ta[i].push_back(ns_per_call(scenes[i].a, 400000, latency));
        tb[i].push_back(ns_per_call(scenes[i].b, 400000, latency));
      }
    for (int i = 0; i < n_scenes; ++i) {
      std::sort(ta[i].begin(), ta[i].end());
      std::sort(tb[i].begin(), tb[i].end());
      const double qa = ta[i][rounds / 4], qb = tb[i][rounds / 4];
      const double ma = ta[i][rounds / 2], mb = tb[i][rounds / 2];
      std::printf("ab %s %s a_ns=%.2f b_ns=%.2f ratio=%.3f (first quartile; medians %.2f %.2f ratio=%.3f)\n",
                  scenes[i].name, latency ? "latency" : "throughput", qa, qb, qb / qa, ma, mb, mb / ma);
    }
  }
}
