// The LDLᵀ solve of M·q̈ = τ − b, unrolled for a scene's fixed size, with a
// relative pivot test that names the joint where M is (nearly) singular;
// dense, or over the entries that can be nonzero where those are known at
// compile time (a tree's mass matrix with more than one branch:
// mass_matrix.hpp), with the same arithmetic on them.
#pragma once
#include <array>
#include <limits>

#include "flange/detail/inline.hpp"

namespace flange::detail {

/// The machine epsilon of a scalar type (of its value part for dual numbers).
template <class T>
constexpr double epsilon() {
  if constexpr (requires { T::v; }) return epsilon<decltype(T::v)>();
  else return double(std::numeric_limits<T>::epsilon());
}

/// The relative pivot test: a pivot d_j of the LDLᵀ at or below
/// tolerance·scale_j, where scale_j is the inertia joint j moves before its
/// projection on the axis, has lost all but about three of its digits to
/// cancellation (its round-off is a few ε·scale_j per operation, N·ε·scale_j
/// in all), so q̈ would be noise.
template <int N, class T>
constexpr double pivot_tolerance() {
  return 1e3 * N * epsilon<T>();
}

/// The outcome of solve_spd: −1, or the first pivot that fails the relative
/// test, with its value and its yardstick.
template <class T>
struct pivot_report {
  int index = -1;
  T d{}, scale{};
};

/// The LDLᵀ factors of a symmetric positive-definite M, computed in place:
/// L below M's diagonal, 1/D here. Factor once, solve for several
/// right-hand sides (a loop scene's constraint solve, dynamics/loop_solve.hpp).
template <int N, class T>
struct ldlt_pivots {
  std::array<T, N> inv_d;
};

/// Which entries of a symmetric N×N matrix can be nonzero (row > column
/// only), known at compile time.
template <int N>
struct sparsity {
  std::array<std::array<bool, N>, N> nz{};
};

/// The entries of L that can be nonzero when M's can be those of p: p and
/// the fill of elimination in order (eliminating j joins every pair of rows
/// below it that are nonzero in column j).
template <int N>
constexpr sparsity<N> factor_sparsity(sparsity<N> p) {
  for (int j = 0; j < N; ++j)
    for (int i = j + 1; i < N; ++i)
      if (p.nz[i][j])
        for (int k = i + 1; k < N; ++k)
          if (p.nz[k][j]) p.nz[k][i] = true;
  return p;
}

/// The factor's pattern as index lists, in the order the dense loops visit
/// them: row i's columns k < i (rows[row_start[i] … row_start[i + 1])), column
/// j's rows i > j (cols[col_start[j] …]), and for each of those entries
/// (i, j), the k < j with L(i, k) and L(j, k) both nonzero (common[…]).
template <int N, int NNZ, int NC>
struct factor_lists {
  std::array<int, N + 1> row_start{}, col_start{};
  std::array<int, NNZ> row_cols{}, col_rows{};
  std::array<int, NNZ + 1> common_start{};
  std::array<int, NC> common{};
};
template <int N>
constexpr int factor_nonzeros(const sparsity<N>& f) {
  int n = 0;
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < i; ++k) n += f.nz[i][k];
  return n;
}
template <int N>
constexpr int factor_common(const sparsity<N>& f) {
  int n = 0;
  for (int j = 0; j < N; ++j)
    for (int i = j + 1; i < N; ++i)
      if (f.nz[i][j])
        for (int k = 0; k < j; ++k) n += f.nz[i][k] && f.nz[j][k];
  return n;
}
template <int N, int NNZ, int NC>
constexpr factor_lists<N, NNZ, NC> make_factor_lists(const sparsity<N>& f) {
  factor_lists<N, NNZ, NC> l;
  int e = 0;
  for (int i = 0; i < N; ++i) {
    l.row_start[i] = e;
    for (int k = 0; k < i; ++k)
      if (f.nz[i][k]) l.row_cols[e++] = k;
  }
  l.row_start[N] = e;
  e = 0;
  int c = 0;
  for (int j = 0; j < N; ++j) {
    l.col_start[j] = e;
    for (int i = j + 1; i < N; ++i)
      if (f.nz[i][j]) {
        l.col_rows[e] = i;
        l.common_start[e++] = c;
        for (int k = 0; k < j; ++k)
          if (f.nz[i][k] && f.nz[j][k]) l.common[c++] = k;
      }
  }
  l.col_start[N] = e;
  l.common_start[e] = c;
  return l;
}

/// The factor's pattern for a matrix whose zeros are not known: every entry.
struct dense_factor {
  static constexpr bool sparse = false;
};

/// The factor's pattern for M's nonzeros given by Pattern::matrix() (a
/// sparsity<N>): its lists, used where they leave out at least half of the
/// dense loops' entries of L (with fewer left out, the dense loops' fixed
/// bounds are faster).
template <class Pattern, int N>
struct sparse_factor {
  static constexpr sparsity<N> fill = factor_sparsity(Pattern::matrix());
  static constexpr int nnz = factor_nonzeros(fill);
  static constexpr auto lists = make_factor_lists<N, nnz, factor_common(fill)>(fill);
  static constexpr bool sparse = nnz < N * (N - 1) / 2 && 2 * nnz <= N * (N - 1) / 2;
};

/// Factors M = L·D·Lᵀ (no square roots). Stops at the first pivot d_j that
/// is not above pivot_tolerance·scale[j] (a joint that moves nothing with
/// inertia, or whose motion repeats other joints') and reports it.
template <int N, class T, class MM, class F = dense_factor>
[[gnu::always_inline]] inline pivot_report<T> ldlt_factor(MM& M, ldlt_pivots<N, T>& f, const T* scale, F = {}) {
  // Column by column: with v_k = L(j, k)·d_k for the row j in hand,
  //   d_j = M(j, j) − Σ_k L(j, k)·v_k,   L(i, j) = (M(i, j) − Σ_k L(i, k)·v_k) / d_j,
  // so each product L·D is formed once. The loop bounds are constants: the
  // compiler unrolls them into straight-line code.
  constexpr double tol = pivot_tolerance<N, T>();
  std::array<T, N> d;
  // With F::sparse, the same sums over the entries that can be nonzero, in
  // the same order (F::lists): the terms left out are exact zeros.
#pragma GCC unroll 16
  for (int j = 0; j < N; ++j) {
    std::array<T, N> v;
    T dj = M(j, j);
    auto row_term = [&](int k) FLANGE_INLINE_LAMBDA {
      v[k] = M(j, k) * d[k];
      dj -= M(j, k) * v[k];
    };
    if constexpr (F::sparse) {
      constexpr auto& l = F::lists;
      for (int e = l.row_start[j]; e < l.row_start[j + 1]; ++e) row_term(l.row_cols[e]);
    } else {
#pragma GCC unroll 16
      for (int k = 0; k < j; ++k) row_term(k);
    }
    if (!(dj > T(tol) * scale[j])) [[unlikely]]
      return {j, dj, scale[j]};
    d[j] = dj;
    f.inv_d[j] = T(1) / dj;
    if constexpr (F::sparse) {
      constexpr auto& l = F::lists;
      for (int e = l.col_start[j]; e < l.col_start[j + 1]; ++e) {
        const int i = l.col_rows[e];
        T x = M(i, j);
        for (int c = l.common_start[e]; c < l.common_start[e + 1]; ++c) x -= M(i, l.common[c]) * v[l.common[c]];
        M(i, j) = x * f.inv_d[j];
      }
    } else {
      // (Rows from the last down: counted up from j + 1, g++ 12 warned of an
      // overflow it imagined where a 2 × 2 factor was inlined in a larger
      // function, -Waggressive-loop-optimizations. Each row is its own.)
#pragma GCC unroll 16
      for (int i = N - 1; i > j; --i) {
        T x = M(i, j);
#pragma GCC unroll 16
        for (int k = 0; k < j; ++k) x -= M(i, k) * v[k];
        M(i, j) = x * f.inv_d[j];  // L(i, j), stored below the diagonal
      }
    }
  }
  return {};
}

/// Row i of a = L⁻¹·r for a sparse factor F: x − Σₖ L(i,k)·a[k] over the
/// entries L can have in that row (x = r[i]).
template <class F, class T, class MM>
[[gnu::always_inline]] inline T forward_row(const MM& M, int i, T x, const T* a) {
  constexpr auto& l = F::lists;
  for (int e = l.row_start[i]; e < l.row_start[i + 1]; ++e) x -= M(i, l.row_cols[e]) * a[l.row_cols[e]];
  return x;
}

/// a = L⁻¹·r and a = L⁻ᵀ·r: the halves of a solve with the factors of
/// ldlt_factor (r and a may be one array).
template <int N, class T, class MM, class F = dense_factor>
[[gnu::always_inline]] inline void ldlt_forward(const MM& M, const T* r, T* a, F = {}) {
  if constexpr (F::sparse) {
#pragma GCC unroll 16
    for (int i = 0; i < N; ++i) a[i] = forward_row<F>(M, i, r[i], a);
    return;
  }
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) {
    T x = r[i];
#pragma GCC unroll 16
    for (int k = 0; k < i; ++k) x -= M(i, k) * a[k];
    a[i] = x;
  }
}
/// The rows a = L⁻¹·r can be nonzero in when r can be in those of mask:
/// mask and every row L joins to one of them (in order: L's row i has
/// columns k < i only).
template <class F, std::size_t N>
constexpr std::array<bool, N> forward_reach(std::array<bool, N> mask) {
  constexpr auto& l = F::lists;
  for (std::size_t i = 0; i < N; ++i)
    for (int e = l.row_start[i]; e < l.row_start[i + 1] && !mask[i]; ++e) mask[i] = mask[l.row_cols[e]];
  return mask;
}
/// a = L⁻¹·r of a sparse factor F where r is zero outside the rows Rows
/// (forward_reach's, in order): a is computed on Rows, with the sparse
/// ldlt_forward's arithmetic, and must be zero elsewhere.
template <class F, auto Rows, class T, class MM, class R>
[[gnu::always_inline]] inline void ldlt_forward_on(const MM& M, R&& r, T* a) {
  for (int i : Rows) a[i] = forward_row<F>(M, i, T(r(i)), a);
}
template <int N, class T, class MM, class F = dense_factor>
[[gnu::always_inline]] inline void ldlt_backward(const MM& M, const T* r, T* a, F = {}) {
  if constexpr (F::sparse) {
    constexpr auto& l = F::lists;
#pragma GCC unroll 16
    for (int i = N - 1; i >= 0; --i) {
      T x = r[i];
      for (int e = l.col_start[i]; e < l.col_start[i + 1]; ++e) x -= M(l.col_rows[e], i) * a[l.col_rows[e]];
      a[i] = x;
    }
    return;
  }
#pragma GCC unroll 16
  for (int i = N - 1; i >= 0; --i) {
    T x = r[i];
#pragma GCC unroll 16
    for (int k = i + 1; k < N; ++k) x -= M(k, i) * a[k];
    a[i] = x;
  }
}

/// a = M⁻¹·r from the factors of ldlt_factor (r and a may be one array).
template <int N, class T, class MM, class F = dense_factor>
[[gnu::always_inline]] inline void ldlt_solve(const MM& M, const ldlt_pivots<N, T>& f, const T* r, T* a, F = {}) {
  ldlt_forward<N>(M, r, a, F{});
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) a[i] *= f.inv_d[i];
  ldlt_backward<N>(M, a, a, F{});
}

/// Solves M·a = r for a symmetric positive-definite M by an unrolled LDLᵀ,
/// reporting a failed pivot (ldlt_factor) instead of solving.
/// Always inlined: for a scene's small systems the call would cost more than
/// a 2×2 solve.
template <int N, class T, class MM, class F = dense_factor>
[[gnu::always_inline]] inline pivot_report<T> solve_spd(MM& M, const T* r, T* a, const T* scale, F = {}) {
  ldlt_pivots<N, T> f;
  const auto p = ldlt_factor<N>(M, f, scale, F{});
  if (p.index < 0) [[likely]]
    ldlt_solve<N>(M, f, r, a, F{});
  return p;
}

}  // namespace flange::detail
