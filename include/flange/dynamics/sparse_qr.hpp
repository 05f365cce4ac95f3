// The triangular factor R of a QR of a tall sparse matrix B (QᵀB = R, Q not
// kept), by Givens rotations row by row (George and Heath's row merge), its
// columns in a fixed order: each row of B is rotated into R from its first
// nonzero column on, so R fills in only where RᵀR = BᵀB does. A banded B
// (a row of loops that share their neighbours' links) gives a banded R, in
// time and memory linear in its size. Rows of R are kept over the range of
// columns they reach ([k, hi[k]]); the triangular solves visit only that
// envelope.
//
// With R, the least change δ = B·(BᵀB)⁻¹·b solving Bᵀ·δ = b is B·R⁻¹·R⁻ᵀ·b
// (the semi-normal equations of the minimum-norm problem, which are as
// accurate as with Q: Paige 1973; Björck, "Numerical Methods for Least
// Squares Problems", 1996, §6.6).
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "flange/detail/inline.hpp"
#include "flange/math/dual.hpp"

namespace flange::detail {

/// Which of a column's N rows can be nonzero, a bit each.
template <int N>
using rows_mask = std::array<std::uint64_t, (N + 63) / 64>;
/// f(i) for each row i in r, in increasing order.
template <std::size_t W, class F>
FLANGE_INLINE void for_rows(const std::array<std::uint64_t, W>& r, F&& f) {
  for (std::size_t w = 0; w < W; ++w)
    for (std::uint64_t bits = r[w]; bits; bits &= bits - 1) f(int(w * 64) + std::countr_zero(bits));
}

/// R of an M-column QR built row by row. Row k exists where has(k), over
/// the columns [k, hi[k]]; a column none of the rows reached (or every row
/// left out) has no row: its direction is not in B's range.
template <int M, class T>
struct givens_r {
  std::array<std::array<T, M>, M> r;
  std::array<int, M> hi;  ///< the last column of row k; −1 where it has none
  std::array<int, M> lo;  ///< the first row that reaches column j (j where none above does)

  givens_r() { clear(); }
  /// Back to no rows (r's entries are left as they are: none is read
  /// outside a row's range).
  void clear() {
    hi.fill(-1);
    for (int j = 0; j < M; ++j) lo[j] = j;
  }
  bool has(int k) const { return hi[k] >= 0; }
  const T& operator()(int i, int j) const { return r[i][j]; }
  /// R(i, j) for i < j, zero where row i does not reach column j.
  T above(int i, int j) const { return hi[i] >= j ? r[i][j] : T(0); }

  /// Rotates a row x of B (dense over the columns [first, last], zero
  /// elsewhere) into R; x is overwritten.
  void add_row(T* x, int first, int last) {
    using std::sqrt;
    for (int k = first; k <= last; ++k) {
      if (exactly_zero(x[k])) continue;  // nothing to rotate away in this column
      if (!has(k)) {  // the first row to reach column k: it becomes R's row k
        for (int j = k; j <= last; ++j) r[k][j] = x[j];
        reach(k, k + 1, last);
        return;
      }
      // Extend the shorter of the two with zeros, so both span [k, end].
      const int end = hi[k] > last ? hi[k] : last;
      for (int j = hi[k] + 1; j <= end; ++j) r[k][j] = T(0);
      for (int j = last + 1; j <= end; ++j) x[j] = T(0);
      reach(k, hi[k] + 1, end);
      last = end;
      const T a = r[k][k], b = x[k];
      const T h = sqrt(a * a + b * b);
      const T c = a / h, s = b / h;
      r[k][k] = h;
      x[k] = T(0);
      for (int j = k + 1; j <= end; ++j) {
        const T u = r[k][j], v = x[j];
        r[k][j] = c * u + s * v;
        x[j] = c * v - s * u;
      }
    }
  }

  /// R of the matrix whose row i (of N) can be nonzero in the columns
  /// touches[i], entry(c, i) in column c, built again without the first
  /// column whose diagonal repeats(c, R(c, c)) says depends on the columns
  /// before it, until none does (a column no row reaches is left out as it
  /// is: it has no row of R and changes nothing).
  template <std::size_t N, class Entry, class Repeats>
  void factor_rows(const std::array<rows_mask<M>, N>& touches, Entry&& entry, Repeats&& repeats) {
    std::array<bool, M> kept;
    kept.fill(true);
    for (;;) {
      clear();
      for (std::size_t i = 0; i < N; ++i) {
        int first = M, last = -1;
        for_rows(touches[i], [&](int c) FLANGE_INLINE_LAMBDA {
          if (!kept[c]) return;
          if (c < first) first = c;
          last = c;
        });
        if (last < 0) continue;
        std::array<T, M> x;
        for (int c = first; c <= last; ++c) x[c] = T(0);
        for_rows(touches[i], [&](int c) FLANGE_INLINE_LAMBDA {
          if (kept[c]) x[c] = entry(c, int(i));
        });
        add_row(x.data(), first, last);
      }
      int dependent = -1;
      for (int c = 0; c < M && dependent < 0; ++c) {
        if (!kept[c]) continue;
        if (!has(c)) kept[c] = false;
        else if (repeats(c, r[c][c])) dependent = c;
      }
      if (dependent < 0) return;
      kept[dependent] = false;
    }
  }

  /// Row k now reaches the columns from … to (its last).
  void reach(int k, int from, int to) {
    for (int j = from; j <= to; ++j)
      if (k < lo[j]) lo[j] = k;
    hi[k] = to;
  }

  /// Solves Rᵀ·u = b over the rows R has (u = 0 elsewhere), from the first
  /// column on.
  void solve_transposed(const T* b, T* u) const {
    for (int j = 0; j < M; ++j) {
      if (!has(j)) {
        u[j] = T(0);
        continue;
      }
      T x = b[j];
      for (int i = lo[j]; i < j; ++i)
        if (hi[i] >= j) x -= r[i][j] * u[i];
      u[j] = x / r[j][j];
    }
  }
  /// Solves R·x = b over the rows R has (x = 0 elsewhere), from the last
  /// column back.
  void solve(const T* b, T* x) const {
    for (int j = M - 1; j >= 0; --j) {
      if (!has(j)) {
        x[j] = T(0);
        continue;
      }
      T s = b[j];
      for (int c = j + 1; c <= hi[j]; ++c) s -= r[j][c] * x[c];
      x[j] = s / r[j][j];
    }
  }
};

}  // namespace flange::detail
