// A block of a row-major matrix placed, turned, into a column-major one: the
// rows of ∂v̇/∂x that the Jacobian's passes fill (a row per rate, read along)
// become the v̇ rows of J's columns (simulate/jacobian.hpp). A pure move of
// numbers: the same to the bit however it is done. Where the processor runs
// AVX2 (detail/cpu.hpp), four rows and four columns at a time, turned in
// registers: four loads and four stores of four numbers where the portable
// code makes sixteen of each.
#pragma once
#include <array>
#include <cstddef>
#include <type_traits>

#include "flange/detail/cpu.hpp"
#include "flange/detail/inline.hpp"

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
#include <immintrin.h>
#endif

namespace flange::detail {

/// The rows' places turned about: row_from[p] is the r with row_to[r] = p.
template <auto row_to>
inline constexpr auto rows_from = [] {
  auto from = row_to;
  for (int r = 0; r < int(row_to.size()); ++r) from[row_to[r]] = r;
  return from;
}();

/// Where each column of dst that col_to names begins, ld numbers a column
/// (−1: none).
template <int ld, auto col_to>
inline constexpr auto column_starts = [] {
  std::array<std::ptrdiff_t, col_to.size()> at{};
  for (std::size_t c = 0; c < col_to.size(); ++c) at[c] = col_to[c] < 0 ? -1 : std::ptrdiff_t(col_to[c]) * ld;
  return at;
}();

/// dst(r0 + row_to[r], col_to[c]) = src(r, c) for every row r of src and
/// column c < col_to.size(): src row-major, ls numbers a row; dst
/// column-major, ld numbers a column; row_to a permutation of 0 … R − 1; a
/// column whose col_to is negative is left alone. Four of src's rows at a
/// time, so that each of dst's columns (ld numbers apart) takes four numbers
/// at a visit and src's rows are read along (the 64-link chain's Jacobian:
/// 67 against 80 µs a number at a time).
template <int ls, int ld, auto row_to, auto col_to>
FLANGE_INLINE void place_transposed_portable(const double* src, double* dst, int r0) {
  constexpr int R = int(row_to.size()), C = int(col_to.size());
  constexpr bool in_order = [] {
    for (int r = 0; r < R; ++r)
      if (row_to[r] != r) return false;
    return true;
  }();
  // Columns from h on go to consecutive columns of dst (all of them on a
  // chain); those before it, where their table says.
  constexpr int h = [] {
    int k = C;
    while (k > 0 && col_to[k - 1] >= 0 && (k == C || col_to[k] == col_to[k - 1] + 1)) --k;
    return k;
  }();
  auto tile = [&](int r, auto width) FLANGE_INLINE_LAMBDA {
    constexpr int w = decltype(width)::value;
    int to_row[w];
    for (int k = 0; k < w; ++k) to_row[k] = in_order ? r + k : row_to[r + k];
    for (int c = 0; c < h; ++c) {
      if (col_to[c] < 0) continue;
      double* to = dst + column_starts<ld, col_to>[c] + r0;
      for (int k = 0; k < w; ++k) to[to_row[k]] = src[(r + k) * ls + c];
    }
    if constexpr (h < C) {
      for (int c = h; c < C; ++c) {
        double* to = dst + (std::ptrdiff_t(col_to[h]) + (c - h)) * ld + r0;
        for (int k = 0; k < w; ++k) to[to_row[k]] = src[(r + k) * ls + c];
      }
    }
  };
  for (int r = 0; r + 4 <= R; r += 4) tile(r, std::integral_constant<int, 4>{});
  if constexpr (R % 4 != 0) tile(R - R % 4, std::integral_constant<int, R % 4>{});
}

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
/// The same in AVX2, by four of dst's rows: a 4 × 4 block of src (the four
/// rows that go there, four numbers along each: a load a row) turned in
/// registers into four columns of four numbers (a store each); the columns
/// and rows left over a number at a time.
template <int ls, int ld, auto row_to, auto col_to>
[[gnu::target("avx2")]] void place_transposed_avx2(const double* src, double* dst, int r0) {
  constexpr int R = int(row_to.size()), C = int(col_to.size()), C4 = C / 4 * 4;
  constexpr auto& from = rows_from<row_to>;
  for (int p = 0; p + 4 <= R; p += 4) {
    const double* a = src + from[p] * ls;
    const double* b = src + from[p + 1] * ls;
    const double* e = src + from[p + 2] * ls;
    const double* f = src + from[p + 3] * ls;
    for (int c = 0; c < C4; c += 4) {
      const __m256d ra = _mm256_loadu_pd(a + c), rb = _mm256_loadu_pd(b + c);
      const __m256d re = _mm256_loadu_pd(e + c), rf = _mm256_loadu_pd(f + c);
      const __m256d lo_ab = _mm256_unpacklo_pd(ra, rb), hi_ab = _mm256_unpackhi_pd(ra, rb);
      const __m256d lo_ef = _mm256_unpacklo_pd(re, rf), hi_ef = _mm256_unpackhi_pd(re, rf);
      const __m256d col[4] = {_mm256_permute2f128_pd(lo_ab, lo_ef, 0x20), _mm256_permute2f128_pd(hi_ab, hi_ef, 0x20),
                              _mm256_permute2f128_pd(lo_ab, lo_ef, 0x31), _mm256_permute2f128_pd(hi_ab, hi_ef, 0x31)};
      for (int j = 0; j < 4; ++j)
        if (col_to[c + j] >= 0) _mm256_storeu_pd(dst + column_starts<ld, col_to>[c + j] + r0 + p, col[j]);
    }
    for (int c = C4; c < C; ++c) {
      if (col_to[c] < 0) continue;
      double* to = dst + column_starts<ld, col_to>[c] + r0 + p;
      to[0] = a[c], to[1] = b[c], to[2] = e[c], to[3] = f[c];
    }
  }
  if constexpr (R % 4 != 0) {
    for (int c = 0; c < C; ++c) {
      if (col_to[c] < 0) continue;
      double* to = dst + column_starts<ld, col_to>[c] + r0;
      for (int p = R - R % 4; p < R; ++p) to[p] = src[from[p] * ls + c];
    }
  }
}
#endif

/// dst(r0 + row_to[r], col_to[c]) = src(r, c), as above, in AVX2 where the
/// processor runs it and src has a block of four rows to turn (with fewer,
/// the portable code inlined: the crane's Jacobian 71 against 73 ns).
template <int ls, int ld, auto row_to, auto col_to>
FLANGE_INLINE void place_transposed(const double* src, double* dst, int r0) {
#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
  if constexpr (row_to.size() >= 4)
    if (cpu_has_avx2) return place_transposed_avx2<ls, ld, row_to, col_to>(src, dst, r0);
#endif
  place_transposed_portable<ls, ld, row_to, col_to>(src, dst, r0);
}

}  // namespace flange::detail
