// The cosine and sine of an angle, and of many angles in one call.
//
// A joint that turns by an angle needs cos φ and sin φ at every evaluation.
// One at a time they are a libm call each (glibc's sincos), a large share
// of a spatial chain's derivative. The links of a scene are known at compile time, so
// dynamics/links.hpp gathers every link's angle into one array first and
// asks for all the cosines and sines at once: cos_sin_batch below. On x86-64
// with glibc that is glibc's own vector math library (libmvec, linked with
// libm): 4 angles per call where the processor has AVX2 (chosen at run time,
// once), 2 per call with the SSE2 every x86-64 has. Elsewhere it is std::cos
// and std::sin, one angle at a time.
//
// What one call saves is measured by tools/probes/sincos_batch.cpp
// (docs/performance.md, "Why the hot path is written as it is").
// libmvec's error bound is 4 ulp (tests/sincos_test.cpp checks it against
// long double for angles up to 10⁶): a rotation off by a few 10⁻¹⁶, far
// below any integrator's tolerance.
//
// Define FLANGE_NO_LIBMVEC to keep the one-at-a-time calls everywhere.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>

#include "flange/detail/cpu.hpp"
#include "flange/detail/inline.hpp"

#if defined(__x86_64__) && defined(__GLIBC__) && !defined(FLANGE_NO_LIBMVEC)
#define FLANGE_HAS_LIBMVEC 1
#include <immintrin.h>
// glibc's vector variants of sin and cos (the x86-64 vector function ABI:
// b = SSE, 2 lanes; d = AVX2, 4 lanes), declared by <math.h> only under
// -ffast-math with OpenMP SIMD, so declared here.
extern "C" {
__m128d _ZGVbN2v_cos(__m128d);
__m128d _ZGVbN2v_sin(__m128d);
__attribute__((target("avx2"))) __m256d _ZGVdN4v_cos(__m256d);
__attribute__((target("avx2"))) __m256d _ZGVdN4v_sin(__m256d);
}
#endif

namespace flange {

/// cos φ and sin φ.
template <class T>
struct cos_sin {
  T c, s;
};

/// cos φ and sin φ for one angle of any scalar type (double, long double, a
/// dual number: found by argument-dependent lookup).
template <class T>
[[nodiscard]] FLANGE_INLINE cos_sin<T> cos_sin_of(const T& phi) {
  using std::cos;
  using std::sin;
  return {cos(phi), sin(phi)};
}

namespace detail {
#ifdef FLANGE_HAS_LIBMVEC
// The angles reach the vector functions in registers, two per SSE register:
// written to memory one by one and read back as one vector, they would stall
// the load (a store cannot forward to a wider load).

/// cos and sin of the four angles (lo, hi) into c[0 … 4), s[0 … 4).
[[gnu::target("avx2")]] inline void cos_sin_avx2(__m128d lo, __m128d hi, double* c, double* s) {
  const __m256d x = _mm256_set_m128d(hi, lo);
  _mm256_storeu_pd(c, _ZGVdN4v_cos(x));
  _mm256_storeu_pd(s, _ZGVdN4v_sin(x));
}
/// cos and sin of the two angles x into c[0 … 2), s[0 … 2).
FLANGE_INLINE void cos_sin_sse2(__m128d x, double* c, double* s) {
  _mm_storeu_pd(c, _ZGVbN2v_cos(x));
  _mm_storeu_pd(s, _ZGVbN2v_sin(x));
}
#endif
}  // namespace detail

/// N angles and their cosines and sines: fill a[0 … N), call compute(),
/// read c and s (or [i]).
template <std::size_t N>
struct cos_sin_batch {
  static constexpr std::size_t padded = (N + 3) / 4 * 4;
  double a[N];
  alignas(32) double c[padded];
  alignas(32) double s[padded];

  FLANGE_INLINE void compute() {
#ifdef FLANGE_HAS_LIBMVEC
    // A lane past the last angle repeats an angle (an angle of 0 would take
    // the vector functions' slow path for small arguments).
    const auto pair = [&](std::size_t i) FLANGE_INLINE_LAMBDA {
      return _mm_set_pd(a[i + 1 < N ? i + 1 : 0], a[i < N ? i : 0]);
    };
    if (detail::cpu_has_avx2)
      for (std::size_t i = 0; i < N; i += 4) detail::cos_sin_avx2(pair(i), pair(i + 2), c + i, s + i);
    else
      for (std::size_t i = 0; i < N; i += 2) detail::cos_sin_sse2(pair(i), c + i, s + i);
#else
    for (std::size_t i = 0; i < N; ++i) c[i] = std::cos(a[i]), s[i] = std::sin(a[i]);
#endif
  }
  [[nodiscard]] FLANGE_INLINE cos_sin<double> operator[](std::size_t i) const { return {c[i], s[i]}; }
};

}  // namespace flange
