// The probes' timer: the median of 15 rounds of 2000 calls of f, in ns a call.
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

template <class F>
double median_ns(F&& f) {
  std::vector<double> t;
  for (int r = 0; r < 15; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 2000; ++i) f();
    t.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / 2000);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
