// Solving M·X = B in place for many right-hand sides, where M = Cᵀ·C is a
// tree's mass matrix factored leaves first (Featherstone's LTL: C has the
// tree's zeros, C(k, a) ≠ 0 only for a = k or an ancestor a of k): both
// triangular solves, as sums into one row of X at a time,
//
//   Cᵀ·Y = B from the leaves:  y_k = (b_k − Σ_{c below k} C(c, k)·y_c) / C(k, k)
//   C·X = Y from the root:     x_k = (y_k − Σ_{a above k} C(k, a)·x_a) / C(k, k)
//
// over a block of X's columns. dynamics/derivatives.hpp solves this way for
// the 2N + 1 columns of ∂v̇/∂x: N²·(2N + 1) multiply-adds on a chain of N
// rates, a large share of the Jacobian's time for long chains.
//
// The tree is a type whose tables are known at compile time (tree_lists
// below, from the nodes' parents). Nodes are numbered 1 … NN − 1 with
// parents first, 0 the root; row k − 1 of X and of C are node k's.
//
// Two kernels, the same sums: tree_solve_block, Eigen's rows of a fixed
// width (SSE2 on x86-64 unless the build asks for more), and on x86-64 where
// the processor has AVX2 and FMA (detail/cpu.hpp, asked once at run time)
// tree_solve_avx2, four columns a register and each multiply-add fused: a
// result differs from the other's in its last bits. tree_solve picks.
// Define FLANGE_NO_AVX2 to keep the first everywhere.
#pragma once
#include <array>

#include <Eigen/Core>

#include "flange/detail/cpu.hpp"
#include "flange/detail/inline.hpp"

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
#define FLANGE_TREE_SOLVE_AVX2 1
#include <immintrin.h>
#endif

namespace flange::detail {

/// The tree of Parents::parent (a std::array: node k's parent, below k; 0
/// the root) with each node's descendants as lists: those of node k are
/// list[start[k]] … list[start[k + 1] − 1], in node order.
template <class Parents>
struct tree_lists {
  static constexpr const auto& parent = Parents::parent;
  static constexpr int NN = int(parent.size());
  static constexpr int total = [] {
    int n = 0;
    for (int c = 1; c < NN; ++c)
      for (int a = parent[c]; a != 0; a = parent[a]) ++n;
    return n;
  }();
  static constexpr std::array<int, NN + 1> start = [] {
    std::array<int, NN + 1> r{};
    for (int c = 1; c < NN; ++c)
      for (int a = parent[c]; a != 0; a = parent[a]) ++r[a + 1];
    for (int k = 1; k <= NN; ++k) r[k] += r[k - 1];
    return r;
  }();
  static constexpr std::array<int, total> list = [] {
    std::array<int, total> r{};
    std::array<int, NN + 1> fill = start;
    for (int c = 1; c < NN; ++c)
      for (int a = parent[c]; a != 0; a = parent[a]) r[fill[a]++] = c;
    return r;
  }();
};

/// Columns c0 … c0 + W of X (rows of ldx numbers, row k − 1 node k's):
/// C(r, c) = C[r + c·ldc] (column-major), inv[k] = 1 / C(k − 1, k − 1).
/// Two sums in turn, so that each waits on its own last product only.
template <class Tree, int W>
FLANGE_INLINE void tree_solve_block(const double* C, int ldc, const double* inv, double* X, int ldx, int c0) {
  constexpr int NN = Tree::NN;
  using Row = Eigen::Matrix<double, 1, W>;
  auto row = [&](int k) FLANGE_INLINE_LAMBDA { return Eigen::Map<Row>(X + (k - 1) * ldx + c0); };
  auto c = [&](int r, int col) FLANGE_INLINE_LAMBDA { return C[(r - 1) + (col - 1) * ldc]; };
  for (int k = NN - 1; k >= 1; --k) {
    Row acc = row(k), acc2 = Row::Zero();
    int e = Tree::start[k];
    const int end = Tree::start[k + 1];
    for (; e + 1 < end; e += 2) {
      acc -= c(Tree::list[e], k) * row(Tree::list[e]);
      acc2 -= c(Tree::list[e + 1], k) * row(Tree::list[e + 1]);
    }
    if (e < end) acc -= c(Tree::list[e], k) * row(Tree::list[e]);
    row(k) = (acc + acc2) * inv[k];
  }
  for (int k = 1; k < NN; ++k) {
    Row acc = row(k), acc2 = Row::Zero();
    int a = Tree::parent[k];
    for (; a != 0 && Tree::parent[a] != 0; a = Tree::parent[Tree::parent[a]]) {
      acc -= c(k, a) * row(a);
      acc2 -= c(k, Tree::parent[a]) * row(Tree::parent[a]);
    }
    if (a != 0) acc -= c(k, a) * row(a);
    row(k) = (acc + acc2) * inv[k];
  }
}

/// The first Cols columns of X (rows of ldx numbers) by tree_solve_block: one block up to 40 columns;
/// else blocks of 16, the last one taking the remainder (16 to 31 columns),
/// so that no block is a narrow tail.
template <class Tree, int Cols>
FLANGE_INLINE void tree_solve_blocks(const double* C, int ldc, const double* inv, double* X, int ldx) {
  if constexpr (Cols <= 40) {
    tree_solve_block<Tree, Cols>(C, ldc, inv, X, ldx, 0);
  } else {
    constexpr int last_block = 16 + Cols % 16;
    for (int c0 = 0; c0 + last_block < Cols; c0 += 16) tree_solve_block<Tree, 16>(C, ldc, inv, X, ldx, c0);
    tree_solve_block<Tree, last_block>(C, ldc, inv, X, ldx, Cols - last_block);
  }
}

/// The row length tree_solve needs for Cols columns: a multiple of four
/// (AVX2's registers), the columns past Cols finite (zeros, say).
constexpr int tree_solve_row(int cols) { return (cols + 3) / 4 * 4; }

#ifdef FLANGE_TREE_SOLVE_AVX2
/// acc[p] −= m[p]·x[p] (V registers of four columns) for the first `count`
/// of the P terms.
template <int V, int P>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_terms(__m256d (&acc)[P][V],
                                                                            const double* const (&x)[P],
                                                                            const double (&m)[P], int count) {
  for (int p = 0; p < P; ++p)
    if (p < count) {
      const __m256d b = _mm256_set1_pd(m[p]);
      for (int v = 0; v < V; ++v) acc[p][v] = _mm256_fnmadd_pd(b, _mm256_loadu_pd(x[p] + 4 * v), acc[p][v]);
    }
}

/// Row xk ← (the P sums of acc added) / its pivot (s = 1 / C(k, k)).
template <int V, int P>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_finish(__m256d (&acc)[P][V], double s,
                                                                             double* xk) {
  const __m256d d = _mm256_set1_pd(s);
  for (int v = 0; v < V; ++v) {
    for (int p = 1; p < P; ++p) acc[0][v] = _mm256_add_pd(acc[0][v], acc[p][v]);
    _mm256_storeu_pd(xk + 4 * v, _mm256_mul_pd(acc[0][v], d));
  }
}

/// The sums start from row xk.
template <int V, int P>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_start(__m256d (&acc)[P][V], const double* xk) {
  for (int v = 0; v < V; ++v) {
    acc[0][v] = _mm256_loadu_pd(xk + 4 * v);
    for (int p = 1; p < P; ++p) acc[p][v] = _mm256_setzero_pd();
  }
}

/// The tile of X's columns c0 … c0 + 4·V (rows of ldx numbers), as
/// tree_solve_block with each product fused, in P sums in turn (each sum a
/// chain of fused multiply-adds, each waiting on the one before).
template <class Tree, int V, int P, int ldx>
[[gnu::target("avx2,fma")]] void tree_solve_tile_avx2(const double* C, int ldc, const double* inv, double* X, int c0) {
  constexpr int NN = Tree::NN;
  __m256d acc[P][V];
  double m[P];
  const double* x[P];
  for (int k = NN - 1; k >= 1; --k) {
    double* xk = X + (k - 1) * ldx + c0;
    tree_solve_start<V, P>(acc, xk);
    const int end = Tree::start[k];
    for (int e = Tree::start[k + 1] - 1; e >= end; e -= P) {
      int count = 0;
      for (int p = 0; p < P; ++p)
        if (e - p >= end) {
          const int d = Tree::list[e - p];
          m[p] = C[(d - 1) + (k - 1) * ldc];
          x[p] = X + (d - 1) * ldx + c0;
          ++count;
        }
      tree_solve_terms<V, P>(acc, x, m, count);
    }
    tree_solve_finish<V, P>(acc, inv[k], xk);
  }
  for (int k = 1; k < NN; ++k) {
    double* xk = X + (k - 1) * ldx + c0;
    tree_solve_start<V, P>(acc, xk);
    for (int a = Tree::parent[k]; a != 0;) {
      int count = 0;
      for (int p = 0; p < P; ++p)
        if (a != 0) {
          m[p] = C[(k - 1) + (a - 1) * ldc];
          x[p] = X + (a - 1) * ldx + c0;
          a = Tree::parent[a];
          ++count;
        }
      tree_solve_terms<V, P>(acc, x, m, count);
    }
    tree_solve_finish<V, P>(acc, inv[k], xk);
  }
}

/// All Row columns of X (rows of Row numbers, a multiple of four), in tiles
/// of 16 columns (four registers, two sums: eight of AVX2's sixteen), the
/// last tile the remainder.
template <class Tree, int Row>
[[gnu::target("avx2,fma")]] void tree_solve_avx2(const double* C, int ldc, const double* inv, double* X) {
  static_assert(Row % 4 == 0);
  constexpr int full = Row / 16, rest = Row % 16;
  for (int t = 0; t < full; ++t) tree_solve_tile_avx2<Tree, 4, 2, Row>(C, ldc, inv, X, 16 * t);
  if constexpr (rest > 0) tree_solve_tile_avx2<Tree, rest / 4, 2, Row>(C, ldc, inv, X, 16 * full);
}
#endif

/// X ← M⁻¹·X for X's first Cols columns, X's rows tree_solve_row(Cols)
/// numbers long: tree_solve_avx2 (every column of the rows) where the
/// processor runs it, else tree_solve_blocks.
template <class Tree, int Cols>
FLANGE_INLINE void tree_solve(const double* C, int ldc, const double* inv, double* X) {
  constexpr int row = tree_solve_row(Cols);
#ifdef FLANGE_TREE_SOLVE_AVX2
  if (cpu_has_avx2_fma) {
    tree_solve_avx2<Tree, row>(C, ldc, inv, X);
    return;
  }
#endif
  tree_solve_blocks<Tree, Cols>(C, ldc, inv, X, row);
}

}  // namespace flange::detail
