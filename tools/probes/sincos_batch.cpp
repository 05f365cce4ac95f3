// Time of N cosines and sines: glibc's sincos one angle at a time, against
// flange's cos_sin_batch (math/sincos.hpp: glibc's libmvec, AVX2 where the
// processor has it, else SSE2), and the SSE2 path forced. Not part of the
// CMake build:
//
//   g++ -std=c++20 -O3 -DANGLES=8 -Iinclude tools/probes/sincos_batch.cpp -o /tmp/sc && /tmp/sc
//
// Prints the median of 7 rounds of 2·10⁵ calls for each, in ns per call.
#include <flange/math/sincos.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#ifndef ANGLES
#define ANGLES 8
#endif
constexpr int N = ANGLES;

namespace {
// The angles as a scene has them (its state), gathered into the batch at
// every call, as dynamics/links.hpp does.
double q[N];
flange::cos_sin_batch<N> b;
[[gnu::noinline]] void one_at_a_time() {
  for (int i = 0; i < N; ++i) sincos(q[i], &b.s[i], &b.c[i]);
}
[[gnu::noinline]] void batch() {
  for (int i = 0; i < N; ++i) b.a[i] = q[i];
  b.compute();
}
#ifdef FLANGE_HAS_LIBMVEC
[[gnu::noinline]] void batch_sse2() {
  for (int i = 0; i < N; ++i) b.a[i] = q[i];
  for (int i = 0; i < N; i += 2)
    flange::detail::cos_sin_sse2(_mm_set_pd(b.a[i + 1 < N ? i + 1 : 0], b.a[i]), b.c + i, b.s + i);
}
#endif

template <class F>
double median_ns(F f) {
  std::vector<double> t;
  for (int r = 0; r < 7; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 200000; ++k) {
      asm volatile("" : : "r"(q) : "memory");
      f();
      asm volatile("" : : "r"(b.c), "r"(b.s) : "memory");
    }
    t.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / 2e5);
  }
  std::sort(t.begin(), t.end());
  return t[3];
}
}  // namespace

int main() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < N; ++i) q[i] = u(rng);
  std::printf("sincos N=%d one_at_a_time_ns=%.1f batch_ns=%.1f", N, median_ns(one_at_a_time), median_ns(batch));
#ifdef FLANGE_HAS_LIBMVEC
  std::printf(" batch_sse2_ns=%.1f avx2=%d", median_ns(batch_sse2), int(flange::detail::cpu_has_avx2));
#endif
  std::printf("\n");
}
