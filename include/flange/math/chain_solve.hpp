// Solving M·X = B in place for many right-hand sides, where M is the mass
// matrix of a chain of N one-rate nodes given by each node's column s_k and
// own inertia A_k (C × C, symmetric; C = 6 numbers in space, 3 in a plane),
// M_ij = s_iᵀ·(A_max(i,j) + … + A_N)·s_j, without forming M: the
// articulated-body factor (Featherstone), from the last node up,
//
//   I_k = A_k + I_{k+1} − U_{k+1}·U_{k+1}ᵀ / D_{k+1},   U_k = I_k·s_k,   D_k = s_kᵀ·U_k,
//
// then for each column of B two sweeps of C numbers a node,
//
//   from the last node:  w_k = (b_k − s_kᵀ·p) / D_k,  p ← p + U_k·w_k   (p = 0 at N + 1)
//   from the first:      x_k = w_k − U_kᵀ·a / D_k,    a ← a + s_k·x_k   (a = 0 at 0)
//
// (the articulated-body algorithm at rest: p is the bias force the nodes
// below pass up, a the acceleration the nodes above pass down). That is
// about 4·C multiply-adds a node and column where the triangular solves of
// M's factor (math/tree_solve.hpp) take N: dynamics/derivatives.hpp solves
// a long chain's 2N + 1 columns of ∂v̇/∂x this way (docs/performance.md,
// "The Jacobian"). D_k is the pivot M's leaves-first LTDL factor (D) would
// meet at node k, and a pivot at or below tol of M_kk stops the factor as it
// stops that one. The factor is whole (factor) or a node at a time (start,
// node, finish), for a pass from the last node up to carry.
//
// Two kernels for many columns, the same sums: chain_solve_blocks, Eigen's
// rows of up to eight columns (SSE2 on x86-64 unless the build asks for
// more), and on x86-64 where the processor has AVX2 and FMA (detail/cpu.hpp)
// chain_solve_avx2, eight columns at a time (twelve in the plane) in
// registers with each multiply-add fused: a result differs from the other's
// in its last bits.
// chain_solve picks. Define FLANGE_NO_AVX2 to keep the first everywhere.
// One column: chain_solve_column, scalar.
#pragma once
#include <array>

#include <Eigen/Core>

#include "flange/detail/cpu.hpp"
#include "flange/detail/inline.hpp"

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
#define FLANGE_CHAIN_SOLVE_AVX2 1
#include <immintrin.h>
#endif

namespace flange::detail {

/// M's articulated-body factor for a chain of N nodes of C numbers; node k
/// (1 … N) at index k − 1.
template <int N, int C>
struct chain_factor {
  static_assert(N >= 1 && C >= 2);
  alignas(32) std::array<std::array<double, C>, N> s, U, Ud;  ///< s_k, U_k, U_k / D_k
  std::array<double, N> inv{};  ///< 1 / D_k
  /// s_kᵀ·U_{k+1} and (U_k / D_k)ᵀ·s_{k−1} (0 past the ends): what the
  /// sweeps take from the neighbour's term alone, so that a node waits on
  /// its neighbour's one number rather than on its C sums.
  std::array<double, N> sU{}, Us{};
  int failed = -1;       ///< the index of the pivot that stopped the factor
  double failed_d = 0;   ///< and its D

  /// Factors from the columns s (index k − 1: node k's) and own inertias
  /// A(k − 1) (a C × C matrix); stops at the first D_k (from node N up) at
  /// or below tol·diag[k − 1], failed then its index. Returns whether every
  /// pivot passed.
  template <class Own>
  bool factor(const std::array<std::array<double, C>, N>& cols, Own A, const double* diag, double tol) {
    start();
    for (int k = N - 1; k >= 0; --k) {
      node(k, cols[k], A(k), diag[k], tol);
      if (failed >= 0) [[unlikely]]
        return false;
    }
    finish();
    return true;
  }

  /// The same factor a node at a time, for a caller's own pass from the
  /// last node up to carry: start(), node(k, …) for k = N − 1 … 0 in turn,
  /// then finish() where failed < 0. Each node's pivot waits on the one
  /// before it (a product, a difference and a division: node() below), so
  /// that the factor alone runs at that latency; inside a pass with work of
  /// its own the processor runs the two side by side. A pivot that fails is kept in failed and
  /// failed_d (the first from node N up), and the factor goes on as if it
  /// had been 1, in finite numbers.
  FLANGE_INLINE void start() {
    J.setZero();
    failed = -1;
  }
  template <class Own>
  FLANGE_INLINE void node(int k, const std::array<double, C>& col, const Own& A, double diag, double tol) {
    using Vec = Eigen::Matrix<double, C, 1>;
    s[k] = col;
    const Eigen::Map<const Vec> sk(s[k].data());
    // J holds the node before's inertia ahead of its own downdate, I_{k+1}
    // + U_{k+1}·U_{k+1}ᵀ / D_{k+1}: U_k and D_k come from J + A_k and that
    // downdate's two numbers on s_k (c = U_{k+1}ᵀ·s_k), so that the chain
    // from one node's division to the next one's is a product and a
    // difference (D_k = s_kᵀ·(J + A_k)·s_k − c²/D_{k+1}), the products with
    // J + A_k running beside the division before it; the matrix's downdate
    // is needed by the node after.
    J += A;
    Vec u = J * sk;
    double d = sk.dot(u);
    if (k + 1 < N) {
      const Eigen::Map<const Vec> up(U[k + 1].data());
      const double c = up.dot(sk), ce = c * inv[k + 1];
      u -= up * ce;
      d -= c * ce;
      // J −= U_{k+1}·U_{k+1}ᵀ / D_{k+1}, written out: as Eigen's outer
      // product, a call the compiler may leave out of line (and so out of
      // the passes' AVX2 build) where a unit holds much code, which ran a
      // 32-link chain's Jacobian 40 % slower.
      for (int j = 0; j < C; ++j)
        for (int i = 0; i < C; ++i) J(i, j) -= Ud[k + 1][i] * U[k + 1][j];
    }
    if (!(d > tol * diag)) [[unlikely]] {
      if (failed < 0) {
        failed = k;
        failed_d = d;
      }
      d = 1;
    }
    const double e = 1 / d;
    inv[k] = e;
    for (int c = 0; c < C; ++c) {
      U[k][c] = u[c];
      Ud[k][c] = u[c] * e;
    }
  }
  FLANGE_INLINE void finish() {
    for (int k = 0; k < N; ++k) {
      double a = 0, b = 0;
      for (int c = 0; c < C; ++c) {
        if (k + 1 < N) a += s[k][c] * U[k + 1][c];
        if (k > 0) b += Ud[k][c] * s[k - 1][c];
      }
      sU[k] = a;
      Us[k] = b;
    }
  }

 private:
  Eigen::Matrix<double, C, C> J;  ///< the last node's inertia before its downdate (node()); zero at the start
};

/// X ← M⁻¹·X for columns c0 … c0 + W − 1 of X (rows of ldx numbers, row
/// k − 1 node k's), in Eigen's rows of W numbers.
template <int N, int C, int W>
FLANGE_INLINE void chain_solve_block(const chain_factor<N, C>& f, double* X, int ldx, int c0) {
  using Row = Eigen::Matrix<double, 1, W>;
  auto row = [&](int k) FLANGE_INLINE_LAMBDA { return Eigen::Map<Row>(X + k * ldx + c0); };
  std::array<Row, C> p;
  for (int c = 0; c < C; ++c) p[c].setZero();
  for (int k = N - 1; k >= 0; --k) {
    Row u = row(k);
    for (int c = 0; c < C; ++c) u -= f.s[k][c] * p[c];
    const Row w = u * f.inv[k];
    row(k) = w;
    for (int c = 0; c < C; ++c) p[c] += f.U[k][c] * w;
  }
  std::array<Row, C>& a = p;
  for (int c = 0; c < C; ++c) a[c].setZero();
  for (int k = 0; k < N; ++k) {
    Row x = row(k);
    for (int c = 0; c < C; ++c) x -= f.Ud[k][c] * a[c];
    row(k) = x;
    for (int c = 0; c < C; ++c) a[c] += f.s[k][c] * x;
  }
}

/// x ← M⁻¹·x for one column x (node k's number at x[k − 1]), as
/// chain_solve_tile_avx2 sweeps: each node's sums hold the nodes beyond its
/// neighbour, whose term comes in last through sU (Us), so that a node
/// waits on its neighbour's one number (a product and a sum) rather than on
/// C sums in a row. Scalar, so that it gives the numbers of the build it is
/// compiled in (the Jacobian's passes: the same in both of theirs, neither
/// of which fuses a multiply-add).
template <int N, int C>
FLANGE_INLINE void chain_solve_column(const chain_factor<N, C>& f, double* x) {
  auto dot = [](const std::array<double, C>& m, const std::array<double, C>& y) FLANGE_INLINE_LAMBDA {
    double e = m[0] * y[0], o = m[1] * y[1];
    for (int c = 2; c < C; c += 2) e += m[c] * y[c];
    for (int c = 3; c < C; c += 2) o += m[c] * y[c];
    return e + o;
  };
  std::array<double, C> p{};
  double w = 0;
  for (int k = N - 1; k >= 0; --k) {  // p: nodes k + 3 … N; w: node k + 2's
    double e = x[k] - dot(f.s[k], p);
    if (k + 1 < N) {
      for (int c = 0; c < C; ++c) p[c] += f.U[k + 1][c] * w;
      e -= f.sU[k] * w;
    }
    x[k] = w = e * f.inv[k];
  }
  std::array<double, C>& a = p;
  a = {};
  for (int k = 0; k < N; ++k) {  // a: nodes 1 … k − 1 (indices below k − 1); w: index k − 1's
    double e = x[k] - dot(f.Ud[k], a);
    if (k > 0) {
      for (int c = 0; c < C; ++c) a[c] += f.s[k - 1][c] * w;
      e -= f.Us[k] * w;
    }
    x[k] = w = e;
  }
}

/// X's first Cols columns (rows of ldx numbers) by chain_solve_block, eight
/// at a time and the remainder.
template <int N, int C, int Cols>
FLANGE_INLINE void chain_solve_blocks(const chain_factor<N, C>& f, double* X, int ldx) {
  constexpr int full = Cols / 8, rest = Cols % 8;
  for (int t = 0; t < full; ++t) chain_solve_block<N, C, 8>(f, X, ldx, 8 * t);
  if constexpr (rest > 0) chain_solve_block<N, C, rest>(f, X, ldx, 8 * full);
}

#ifdef FLANGE_CHAIN_SOLVE_AVX2
/// x −= Σ_c m[c]·y[c] (V registers of four columns each), the even c into
/// x and the odd ones into a second sum taken away at the end.
template <int C, int V>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void chain_solve_dot(__m256d (&x)[V], const double* m,
                                                                            const __m256d (&y)[C][V]) {
  __m256d e[V];
  const __m256d m1 = _mm256_set1_pd(m[1]);
  for (int v = 0; v < V; ++v) e[v] = _mm256_mul_pd(m1, y[1][v]);
  for (int c = 0; c < C; c += 2) {
    const __m256d b = _mm256_set1_pd(m[c]);
    for (int v = 0; v < V; ++v) x[v] = _mm256_fnmadd_pd(b, y[c][v], x[v]);
  }
  for (int c = 3; c < C; c += 2) {
    const __m256d b = _mm256_set1_pd(m[c]);
    for (int v = 0; v < V; ++v) e[v] = _mm256_fmadd_pd(b, y[c][v], e[v]);
  }
  for (int v = 0; v < V; ++v) x[v] = _mm256_sub_pd(x[v], e[v]);
}

/// Both sweeps over columns c0 … c0 + 4·V of X (rows of ldx numbers). The
/// sums over p (and a) hold the nodes beyond the neighbour; the
/// neighbour's term comes in last through sU (Us), off the sums' path.
template <int N, int C, int V>
[[gnu::target("avx2,fma")]] void chain_solve_tile_avx2(const chain_factor<N, C>& f, double* X, int ldx, int c0) {
  __m256d p[C][V], w[V];
  for (int v = 0; v < V; ++v) {
    w[v] = _mm256_setzero_pd();
    for (int c = 0; c < C; ++c) p[c][v] = _mm256_setzero_pd();
  }
  for (int k = N - 1; k >= 0; --k) {  // p: nodes k + 3 … N; w: node k + 2's
    double* xk = X + k * ldx + c0;
    __m256d x[V];
    for (int v = 0; v < V; ++v) x[v] = _mm256_loadu_pd(xk + 4 * v);
    chain_solve_dot<C, V>(x, f.s[k].data(), p);
    if (k + 1 < N) {
      for (int c = 0; c < C; ++c) {
        const __m256d b = _mm256_set1_pd(f.U[k + 1][c]);
        for (int v = 0; v < V; ++v) p[c][v] = _mm256_fmadd_pd(b, w[v], p[c][v]);
      }
      const __m256d g = _mm256_set1_pd(f.sU[k]);
      for (int v = 0; v < V; ++v) x[v] = _mm256_fnmadd_pd(g, w[v], x[v]);
    }
    const __m256d d = _mm256_set1_pd(f.inv[k]);
    for (int v = 0; v < V; ++v) {
      w[v] = _mm256_mul_pd(x[v], d);
      _mm256_storeu_pd(xk + 4 * v, w[v]);
    }
  }
  for (int v = 0; v < V; ++v)
    for (int c = 0; c < C; ++c) p[c][v] = _mm256_setzero_pd();
  __m256d(&a)[C][V] = p;
  for (int k = 0; k < N; ++k) {  // a: nodes 1 … k − 1 (indices below k − 1); w: index k − 1's
    double* xk = X + k * ldx + c0;
    __m256d x[V];
    for (int v = 0; v < V; ++v) x[v] = _mm256_loadu_pd(xk + 4 * v);
    chain_solve_dot<C, V>(x, f.Ud[k].data(), a);
    if (k > 0) {
      for (int c = 0; c < C; ++c) {
        const __m256d b = _mm256_set1_pd(f.s[k - 1][c]);
        for (int v = 0; v < V; ++v) a[c][v] = _mm256_fmadd_pd(b, w[v], a[c][v]);
      }
      const __m256d g = _mm256_set1_pd(f.Us[k]);
      for (int v = 0; v < V; ++v) x[v] = _mm256_fnmadd_pd(g, w[v], x[v]);
    }
    for (int v = 0; v < V; ++v) {
      w[v] = x[v];
      _mm256_storeu_pd(xk + 4 * v, x[v]);
    }
  }
}

/// The first Cols4 columns of X (a multiple of four; rows of Row numbers),
/// in tiles of eight (two registers of sums for each of p's C numbers), or
/// of twelve in the plane (C = 3: three registers each, nine of sums in all,
/// which the sixteen hold with the tile's x and w; three chains of products
/// in flight rather than two hide more of each node's wait on its
/// neighbour), the last tile the remainder.
template <int N, int C, int Cols4, int Row>
[[gnu::target("avx2,fma")]] void chain_solve_avx2(const chain_factor<N, C>& f, double* X) {
  static_assert(Cols4 % 4 == 0 && Cols4 <= Row);
  constexpr int T = C <= 3 ? 12 : 8;
  constexpr int full = Cols4 / T, rest = Cols4 % T;
  for (int t = 0; t < full; ++t) chain_solve_tile_avx2<N, C, T / 4>(f, X, Row, T * t);
  if constexpr (rest > 0) chain_solve_tile_avx2<N, C, rest / 4>(f, X, Row, T * full);
}
#endif

/// X ← M⁻¹·X for X's first Cols columns, X's rows Row numbers long (a
/// multiple of four, the columns past Cols finite up to the next multiple
/// of four): chain_solve_avx2 (the columns up to that multiple) where the
/// processor runs it, else chain_solve_blocks.
template <int N, int C, int Cols, int Row>
FLANGE_INLINE void chain_solve(const chain_factor<N, C>& f, double* X) {
#ifdef FLANGE_CHAIN_SOLVE_AVX2
  if (cpu_has_avx2_fma) {
    chain_solve_avx2<N, C, (Cols + 3) / 4 * 4, Row>(f, X);
    return;
  }
#endif
  chain_solve_blocks<N, C, Cols>(f, X, Row);
}

}  // namespace flange::detail
