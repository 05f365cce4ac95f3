// Solving M·X = B in place for many right-hand sides, where M = Lᵀ·D·L is a
// tree's mass matrix factored leaves first without square roots
// (Featherstone's LTDL: L is unit and has the tree's zeros, L(k, a) ≠ 0 only
// for a = k or an ancestor a of k; D is diagonal). The factor is held in one
// square array C, column-major: below the diagonal U = D·L, what the
// elimination leaves in M (C(k, a) = D_k·L(k, a), a above k), and above it
// L itself, transposed (C(a, k) = L(k, a)); inv[k] = 1 / D_k. Both
// triangular solves, as sums into one row of X at a time over a block of X's
// columns, each reading its factors down column k of C, one number apart:
//
//   Lᵀ·D·Y = B from the leaves:  y_k = (b_k − Σ_{c below k} C(c, k)·y_c) / D_k
//   L·X = Y from the root:        x_k = y_k − Σ_{a above k} C(a, k)·x_a
//
// Against a Cholesky factor (M = Cᵀ·C) the factor takes no square root, on
// whose latency each node's pivot waited, and the rows from the root are
// not scaled (docs/performance.md, "The Jacobian"). dynamics/derivatives.hpp
// solves this way for the 2N + 1 columns of ∂v̇/∂x: N²·(2N + 1)
// multiply-adds on a chain of N rates, a large share of the Jacobian's time
// for long chains.
//
// The tree is a type whose tables are known at compile time (tree_runs
// below, from the nodes' parents: each node's descendants and ancestors as
// runs of consecutive nodes). Nodes are numbered 1 … NN − 1 with parents
// first, 0 the root; row k − 1 of X and of C are node k's. X's rows are
// read four numbers at a time: where X starts on a 32-byte boundary, as
// simulate/jacobian.hpp places it, no read straddles two cache lines.
//
// Two kernels, the same sums: tree_solve_block, Eigen's rows of a fixed
// width (SSE2 on x86-64 unless the build asks for more), and on x86-64 where
// the processor has AVX2 and FMA (detail/cpu.hpp, asked once at run time)
// tree_solve_avx2, four columns a register and each multiply-add fused: a
// result differs from the other's in its last bits. tree_solve picks.
// Define FLANGE_NO_AVX2 to keep the first everywhere.
#pragma once
#include <array>
#include <utility>

#include <Eigen/Core>

#include "flange/detail/cpu.hpp"
#include "flange/detail/inline.hpp"
#include "flange/detail/static_for.hpp"

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
#define FLANGE_TREE_SOLVE_AVX2 1
#include <immintrin.h>
#endif

namespace flange::detail {

/// Nodes lo … hi − 1.
struct node_run {
  int lo, hi;
};

/// The runs of consecutive nodes among x = 1 … NN − 1 for which
/// in(k, x) holds, for each node k = 1 … NN − 1 in turn: their count, and
/// into start (where node k's begin) and runs when given.
template <int NN, class In>
constexpr int collect_runs(In in, std::array<int, NN + 1>* start, node_run* runs) {
  int n = 0;
  for (int k = 1; k < NN; ++k) {
    if (start) (*start)[k] = n;
    for (int x = 1; x < NN; ++x) {
      if (!in(k, x) || (x > 1 && in(k, x - 1))) continue;
      int hi = x + 1;
      while (hi < NN && in(k, hi)) ++hi;
      if (runs) runs[n] = {x, hi};
      ++n;
    }
  }
  if (start) (*start)[NN] = n;
  return n;
}

/// The tree of Parents::parent (a std::array: node k's parent, below k; 0
/// the root) with each node's descendants and its ancestors as runs of
/// consecutive nodes, in node order: those of node k are below[b] for b in
/// below_start[k] … below_start[k + 1] − 1, and above[…] likewise. A chain
/// is one run each way; a tree numbered depth first has one run below each
/// node, and above it one per branch on its way to the root. The sums
/// then walk rows and factor entries a fixed stride apart, with no table
/// read per term.
template <class Parents>
struct tree_runs {
  static constexpr const auto& parent = Parents::parent;
  static constexpr int NN = int(parent.size());
  /// up[x][a]: a is a strict ancestor of x.
  static constexpr auto up = [] {
    std::array<std::array<bool, NN>, NN> r{};
    for (int x = 1; x < NN; ++x)
      for (int a = parent[x]; a != 0; a = parent[a]) r[x][a] = true;
    return r;
  }();
  static constexpr auto is_below = [](int k, int x) { return up[x][k]; };
  static constexpr auto is_above = [](int k, int x) { return up[k][x]; };
  static constexpr std::array<int, NN + 1> below_start = [] {
    std::array<int, NN + 1> r{};
    collect_runs<NN>(is_below, &r, nullptr);
    return r;
  }();
  static constexpr std::array<int, NN + 1> above_start = [] {
    std::array<int, NN + 1> r{};
    collect_runs<NN>(is_above, &r, nullptr);
    return r;
  }();
  static constexpr std::array<node_run, below_start[NN]> below = [] {
    std::array<node_run, below_start[NN]> r{};
    collect_runs<NN>(is_below, nullptr, r.data());
    return r;
  }();
  static constexpr std::array<node_run, above_start[NN]> above = [] {
    std::array<node_run, above_start[NN]> r{};
    collect_runs<NN>(is_above, nullptr, r.data());
    return r;
  }();
  /// Rows the AVX2 kernel solves as a pair: from the leaves, k and k − 1
  /// where k is k − 1's only child (the nodes below k − 1 are k and those
  /// below k); from the root, k and k + 1 where k is k + 1's parent (the
  /// nodes above k + 1 are k and those above k). pair_from_leaves[k] and
  /// pair_from_root[k] say so of the pair's first row, k.
  static constexpr std::array<bool, NN> pair_from_leaves = [] {
    std::array<bool, NN> r{};
    for (int k = 2; k < NN; ++k) {
      r[k] = true;
      for (int x = 1; x < NN; ++x)
        if (up[x][k - 1] != (x == k || up[x][k])) r[k] = false;
    }
    return r;
  }();
  static constexpr std::array<bool, NN> pair_from_root = [] {
    std::array<bool, NN> r{};
    for (int k = 1; k + 1 < NN; ++k) r[k] = parent[k + 1] == k;
    return r;
  }();
  /// Node k's runs below it (Below) or above it, as [first, last).
  template <bool Below>
  static constexpr std::pair<const node_run*, const node_run*> runs_of(int k) {
    const node_run* r = Below ? below.data() : above.data();
    const auto& start = Below ? below_start : above_start;
    return {r + start[k], r + start[k + 1]};
  }
};

/// The factor entries that multiply run r's rows in row k's sum, one
/// number apart down column k of C: from the leaves (r below k) U(d, k)
/// below the diagonal, from the root (r above k) L(k, a) above it.
FLANGE_INLINE const double* run_factors(const double* C, int ldc, int k, node_run r) {
  return C + (r.lo - 1) + (k - 1) * ldc;
}

/// Columns c0 … c0 + W of X (rows of ldx numbers, row k − 1 node k's):
/// C(r, c) = C[r + c·ldc] (column-major, the factor as the header says),
/// inv[k] = 1 / D_k. Row k from the leaves or from the root, in two sums in
/// turn, so that each waits on its own last product only; tree_solve_block:
/// every row.
template <class Tree, int W, bool FromLeaves>
FLANGE_INLINE void tree_solve_block_row(const double* C, int ldc, const double* inv, double* X, int ldx, int c0,
                                        int k) {
  using Row = Eigen::Matrix<double, 1, W>;
  auto row = [&](int n) FLANGE_INLINE_LAMBDA { return Eigen::Map<Row>(X + (n - 1) * ldx + c0); };
  Row acc = row(k), acc2 = Row::Zero();
  for (auto [r, last] = Tree::template runs_of<FromLeaves>(k); r != last; ++r) {
    const double* m = run_factors(C, ldc, k, *r);
    int d = r->lo;
    for (; d + 1 < r->hi; d += 2, m += 2) {
      acc -= m[0] * row(d);
      acc2 -= m[1] * row(d + 1);
    }
    if (d < r->hi) acc -= m[0] * row(d);
  }
  if constexpr (FromLeaves) row(k) = (acc + acc2) * inv[k];
  else row(k) = acc + acc2;
}
/// Trees of at most this many nodes (the root included) are walked with
/// each row's number a constant: every run's bounds known, each sum written
/// out (on a scene of a few rates the loops and their tables cost more than
/// the sums). The same products in the same order. A single column (the
/// analytic derivatives' v̇, before their 2N + 1 columns) up to
/// unrolled_column_nodes: walked by its tables, its one product a visit, it
/// cost as much as the 2N + 1 columns' solve after it (two legs of one joint
/// on a floating base, 8 nodes: about 1,000 instructions each).
inline constexpr int unrolled_tree_nodes = 8, unrolled_column_nodes = 24;

template <class Tree, int W>
FLANGE_INLINE void tree_solve_block(const double* C, int ldc, const double* inv, double* X, int ldx, int c0) {
  constexpr int NN = Tree::NN;
  if constexpr (NN <= (W == 1 ? unrolled_column_nodes : unrolled_tree_nodes)) {
    static_for<NN - 1>([&](auto i) FLANGE_INLINE_LAMBDA {
      tree_solve_block_row<Tree, W, true>(C, ldc, inv, X, ldx, c0, NN - 1 - decltype(i)::value);
    });
    static_for<NN - 1>([&](auto i) FLANGE_INLINE_LAMBDA {
      tree_solve_block_row<Tree, W, false>(C, ldc, inv, X, ldx, c0, 1 + decltype(i)::value);
    });
  } else {
    for (int k = NN - 1; k >= 1; --k) tree_solve_block_row<Tree, W, true>(C, ldc, inv, X, ldx, c0, k);
    for (int k = 1; k < NN; ++k) tree_solve_block_row<Tree, W, false>(C, ldc, inv, X, ldx, c0, k);
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
/// acc[0], acc[1] −= the run's rows (x, x + ldx, …; V registers of four
/// columns each) times m[0], m[1], m[2], …, the two sums in turn.
template <int V>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_run(__m256d (&acc)[2][V], const double* m,
                                                                          const double* x, int ldx, int n) {
  int i = 0;
  for (; i + 1 < n; i += 2, m += 2, x += 2 * ldx) {
    const __m256d b0 = _mm256_set1_pd(m[0]), b1 = _mm256_set1_pd(m[1]);
    for (int v = 0; v < V; ++v) {
      acc[0][v] = _mm256_fnmadd_pd(b0, _mm256_loadu_pd(x + 4 * v), acc[0][v]);
      acc[1][v] = _mm256_fnmadd_pd(b1, _mm256_loadu_pd(x + ldx + 4 * v), acc[1][v]);
    }
  }
  if (i < n) {
    const __m256d b0 = _mm256_set1_pd(m[0]);
    for (int v = 0; v < V; ++v) acc[0][v] = _mm256_fnmadd_pd(b0, _mm256_loadu_pd(x + 4 * v), acc[0][v]);
  }
}

/// Row xk ← the two sums added, from the leaves divided by its pivot
/// (s = 1 / D_k).
template <int V, bool FromLeaves>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_finish(__m256d (&acc)[2][V], double s,
                                                                             double* xk) {
  const __m256d d = _mm256_set1_pd(s);
  for (int v = 0; v < V; ++v) {
    const __m256d sum = _mm256_add_pd(acc[0][v], acc[1][v]);
    _mm256_storeu_pd(xk + 4 * v, FromLeaves ? _mm256_mul_pd(sum, d) : sum);
  }
}

/// The sums start from row xk.
template <int V>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_start(__m256d (&acc)[2][V], const double* xk) {
  for (int v = 0; v < V; ++v) {
    acc[0][v] = _mm256_loadu_pd(xk + 4 * v);
    acc[1][v] = _mm256_setzero_pd();
  }
}

/// Row k of the tile of X's columns c0 … c0 + 4·V (rows of ldx numbers):
/// from the leaves (the nodes below k) or from the root (the nodes above k).
template <class Tree, int V, int ldx, bool FromLeaves>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_row_avx2(const double* C, int ldc,
                                                                               const double* inv, double* X, int c0,
                                                                               int k) {
  __m256d acc[2][V];
  double* xk = X + (k - 1) * ldx + c0;
  tree_solve_start<V>(acc, xk);
  for (auto [r, last] = Tree::template runs_of<FromLeaves>(k); r != last; ++r)
    tree_solve_run<V>(acc, run_factors(C, ldc, k, *r), X + (r->lo - 1) * ldx + c0, ldx, r->hi - r->lo);
  tree_solve_finish<V, FromLeaves>(acc, inv[k], xk);
}

/// Rows a and b of the tile, b next to a on a's far side (from the leaves
/// b = a − 1, from the root b = a + 1; Tree::pair_from_leaves[a] or
/// pair_from_root[a]): both sums over the nodes of a's runs at once, each
/// row of X they read loaded once for the two (eight registers of sums, one
/// each); then a's row, and b's sum takes it.
template <class Tree, int V, int ldx, bool FromLeaves>
[[gnu::target("avx2,fma"), gnu::always_inline]] inline void tree_solve_pair_avx2(const double* C, int ldc,
                                                                                const double* inv, double* X, int c0,
                                                                                int a) {
  const int b = FromLeaves ? a - 1 : a + 1;
  __m256d sa[V], sb[V];
  double *xa = X + (a - 1) * ldx + c0, *xb = X + (b - 1) * ldx + c0;
  for (int v = 0; v < V; ++v) {
    sa[v] = _mm256_loadu_pd(xa + 4 * v);
    sb[v] = _mm256_loadu_pd(xb + 4 * v);
  }
  for (auto [r, last] = Tree::template runs_of<FromLeaves>(a); r != last; ++r) {
    const double *ma = run_factors(C, ldc, a, *r), *mb = run_factors(C, ldc, b, *r);
    const double* x = X + (r->lo - 1) * ldx + c0;
    for (int i = 0, n = r->hi - r->lo; i < n; ++i, ++ma, ++mb, x += ldx) {
      const __m256d fa = _mm256_set1_pd(*ma), fb = _mm256_set1_pd(*mb);
      for (int v = 0; v < V; ++v) {
        const __m256d xv = _mm256_loadu_pd(x + 4 * v);
        sa[v] = _mm256_fnmadd_pd(fa, xv, sa[v]);
        sb[v] = _mm256_fnmadd_pd(fb, xv, sb[v]);
      }
    }
  }
  const __m256d da = _mm256_set1_pd(inv[a]), db = _mm256_set1_pd(inv[b]);
  const __m256d fab = _mm256_set1_pd(*run_factors(C, ldc, b, node_run{a, a + 1}));
  for (int v = 0; v < V; ++v) {
    const __m256d ra = FromLeaves ? _mm256_mul_pd(sa[v], da) : sa[v];
    _mm256_storeu_pd(xa + 4 * v, ra);
    const __m256d rb = _mm256_fnmadd_pd(fab, ra, sb[v]);
    _mm256_storeu_pd(xb + 4 * v, FromLeaves ? _mm256_mul_pd(rb, db) : rb);
  }
}

/// The tile of X's columns c0 … c0 + 4·V (rows of ldx numbers), as
/// tree_solve_block with each product fused: rows in pairs where the tree
/// lets them (all of a chain's), else one at a time. (Walked by loops at
/// every size: written out for small trees, as tree_solve_block is, the
/// planar 4-link chain's jacobian() took 323 against 275 ns,
/// medians of 15 runs in turns.)
template <class Tree, int V, int ldx>
[[gnu::target("avx2,fma")]] void tree_solve_tile_avx2(const double* C, int ldc, const double* inv, double* X, int c0) {
  constexpr int NN = Tree::NN;
  for (int k = NN - 1; k >= 1;)
    if (Tree::pair_from_leaves[k]) {
      tree_solve_pair_avx2<Tree, V, ldx, true>(C, ldc, inv, X, c0, k);
      k -= 2;
    } else {
      tree_solve_row_avx2<Tree, V, ldx, true>(C, ldc, inv, X, c0, k--);
    }
  for (int k = 1; k < NN;)
    if (Tree::pair_from_root[k]) {
      tree_solve_pair_avx2<Tree, V, ldx, false>(C, ldc, inv, X, c0, k);
      k += 2;
    } else {
      tree_solve_row_avx2<Tree, V, ldx, false>(C, ldc, inv, X, c0, k++);
    }
}

/// The first Cols4 columns of X (a multiple of four; rows of Row numbers),
/// in tiles of 24 columns (a row's two sums or a pair's: twelve of AVX2's sixteen
/// registers, the broadcast factors and a row's load the rest), the last
/// tile the remainder. Each tile walks the whole tree: against tiles of 16,
/// the 16-link chain's jacobian() 4.67 → 4.48 µs, a floating tree of 64 leg
/// joints 42.4 → 40.6 µs (medians of five runs in turns); every column's
/// sums are the same either way.
template <class Tree, int Cols4, int Row>
[[gnu::target("avx2,fma")]] void tree_solve_avx2(const double* C, int ldc, const double* inv, double* X) {
  static_assert(Cols4 % 4 == 0 && Cols4 <= Row);
  constexpr int tile = 24, full = Cols4 / tile, rest = Cols4 % tile;
  for (int t = 0; t < full; ++t) tree_solve_tile_avx2<Tree, tile / 4, Row>(C, ldc, inv, X, tile * t);
  if constexpr (rest > 0) tree_solve_tile_avx2<Tree, rest / 4, Row>(C, ldc, inv, X, tile * full);
}
#endif

/// X ← M⁻¹·X for X's first Cols columns, X's rows Row numbers long (at
/// least tree_solve_row(Cols), the columns past Cols finite up to it):
/// tree_solve_avx2 (the columns up to tree_solve_row(Cols)) where the
/// processor runs it, else tree_solve_blocks.
template <class Tree, int Cols, int Row = tree_solve_row(Cols)>
FLANGE_INLINE void tree_solve(const double* C, int ldc, const double* inv, double* X) {
  static_assert(Row % 4 == 0 && tree_solve_row(Cols) <= Row);
#ifdef FLANGE_TREE_SOLVE_AVX2
  if (cpu_has_avx2_fma) {
    tree_solve_avx2<Tree, tree_solve_row(Cols), Row>(C, ldc, inv, X);
    return;
  }
#endif
  tree_solve_blocks<Tree, Cols>(C, ldc, inv, X, Row);
}

}  // namespace flange::detail
