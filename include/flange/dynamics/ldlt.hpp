// The dense LDLᵀ solve of M·q̈ = τ − b, unrolled for a scene's fixed size,
// with a relative pivot test that names the joint where M is (nearly) singular.
#pragma once
#include <array>
#include <limits>

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

/// Factors M = L·D·Lᵀ (no square roots). Stops at the first pivot d_j that
/// is not above pivot_tolerance·scale[j] (a joint that moves nothing with
/// inertia, or whose motion repeats other joints') and reports it.
template <int N, class T, class MM>
[[gnu::always_inline]] inline pivot_report<T> ldlt_factor(MM& M, ldlt_pivots<N, T>& f, const T* scale) {
  // Column by column: with v_k = L(j, k)·d_k for the row j in hand,
  //   d_j = M(j, j) − Σ_k L(j, k)·v_k,   L(i, j) = (M(i, j) − Σ_k L(i, k)·v_k) / d_j,
  // so each product L·D is formed once. The loop bounds are constants: the
  // compiler unrolls them into straight-line code.
  constexpr double tol = pivot_tolerance<N, T>();
  std::array<T, N> d;
#pragma GCC unroll 16
  for (int j = 0; j < N; ++j) {
    std::array<T, N> v;
    T dj = M(j, j);
#pragma GCC unroll 16
    for (int k = 0; k < j; ++k) {
      v[k] = M(j, k) * d[k];
      dj -= M(j, k) * v[k];
    }
    if (!(dj > T(tol) * scale[j])) [[unlikely]]
      return {j, dj, scale[j]};
    d[j] = dj;
    f.inv_d[j] = T(1) / dj;
#pragma GCC unroll 16
    for (int i = j + 1; i < N; ++i) {
      T x = M(i, j);
#pragma GCC unroll 16
      for (int k = 0; k < j; ++k) x -= M(i, k) * v[k];
      M(i, j) = x * f.inv_d[j];  // L(i, j), stored below the diagonal
    }
  }
  return {};
}

/// a = L⁻¹·r and a = L⁻ᵀ·r: the halves of a solve with the factors of
/// ldlt_factor (r and a may be one array).
template <int N, class T, class MM>
[[gnu::always_inline]] inline void ldlt_forward(const MM& M, const T* r, T* a) {
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) {
    T x = r[i];
#pragma GCC unroll 16
    for (int k = 0; k < i; ++k) x -= M(i, k) * a[k];
    a[i] = x;
  }
}
template <int N, class T, class MM>
[[gnu::always_inline]] inline void ldlt_backward(const MM& M, const T* r, T* a) {
#pragma GCC unroll 16
  for (int i = N - 1; i >= 0; --i) {
    T x = r[i];
#pragma GCC unroll 16
    for (int k = i + 1; k < N; ++k) x -= M(k, i) * a[k];
    a[i] = x;
  }
}

/// a = M⁻¹·r from the factors of ldlt_factor (r and a may be one array).
template <int N, class T, class MM>
[[gnu::always_inline]] inline void ldlt_solve(const MM& M, const ldlt_pivots<N, T>& f, const T* r, T* a) {
  ldlt_forward<N>(M, r, a);
#pragma GCC unroll 16
  for (int i = 0; i < N; ++i) a[i] *= f.inv_d[i];
  ldlt_backward<N>(M, a, a);
}

/// Solves M·a = r for a symmetric positive-definite M by an unrolled LDLᵀ,
/// reporting a failed pivot (ldlt_factor) instead of solving.
/// Always inlined: for a scene's small systems the call would cost more than
/// a 2×2 solve.
template <int N, class T, class MM>
[[gnu::always_inline]] inline pivot_report<T> solve_spd(MM& M, const T* r, T* a, const T* scale) {
  ldlt_pivots<N, T> f;
  const auto p = ldlt_factor<N>(M, f, scale);
  if (p.index < 0) [[likely]]
    ldlt_solve<N>(M, f, r, a);
  return p;
}

}  // namespace flange::detail
