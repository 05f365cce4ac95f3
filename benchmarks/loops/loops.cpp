// The cost of closed loops as their number grows (docs/loops.md, "Cost"):
//
//   build/benchmarks/loops
//
// A row of N parallelogram windows (N loops sharing posts), for each size
// the build has: first checked (every post's θ̈ against the closed form, and
// the projection's closure), then the derivative and the projection timed
// in turns, one line per size,
//
//   loops window_row windows=<n> derivative_ns=<x> projection_ns=<y>
//
// then the exponent p of a least-squares fit ns ∝ N^p over N = 10 and up:
//
//   fit window_row windows=10..<max> derivative_exponent=<p> projection_exponent=<p>
//
// The default build has 2 and 10 windows; 20 and 40 need
//   cmake -S . -B build -DFLANGE_SCALE_FULL=ON && cmake --build build --target loops
#include <algorithm>
#include <cstdio>
#include <utility>

#include "loops.hpp"


int main() {
  auto cases = loops::cases();
  std::sort(cases.begin(), cases.end(), [](const auto& a, const auto& b) { return a.windows < b.windows; });
  std::vector<std::pair<double, double>> d, p;
  for (const auto& c : cases) {
    const auto r = c.run();
    if (r.windows >= 10) {
      d.emplace_back(r.windows, r.derivative_ns);
      p.emplace_back(r.windows, r.projection_ns);
    }
  }
  if (d.size() >= 2)
    std::printf("fit window_row windows=10..%.0f derivative_exponent=%.2f projection_exponent=%.2f\n", d.back().first,
                rounds::exponent(d), rounds::exponent(p));
}
