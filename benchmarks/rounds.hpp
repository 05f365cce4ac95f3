// Timing in rounds, shared by the benchmarks that time two things in turns
// (scale/, loops/): a block of calls long enough for the clock, the median
// over the rounds, and the exponent of a power law through the results.
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

namespace rounds {

/// Calls per timed block: enough for about 1 ms.
template <class F>
long calls_for(F&& f) {
  long n = 1;
  for (;;) {
    const auto t0 = std::chrono::steady_clock::now();
    for (long k = 0; k < n; ++k) f();
    if (std::chrono::steady_clock::now() - t0 > std::chrono::microseconds(1000)) return n;
    n *= 2;
  }
}

/// The time per call of a block of n calls, in ns.
template <class F>
double block_ns(F&& f, long n) {
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < n; ++k) f();
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / double(n);
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// The exponent p of the least-squares fit y ∝ x^p through the points (x, y).
inline double exponent(const std::vector<std::pair<double, double>>& pts) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : pts) {
    sx += std::log(x);
    sy += std::log(y);
    sxx += std::log(x) * std::log(x);
    sxy += std::log(x) * std::log(y);
  }
  const double n = double(pts.size());
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace rounds
