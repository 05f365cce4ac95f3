// The triangular solves of a tree's factored mass matrix (math/tree_solve.hpp),
// both kernels (Eigen's rows, and AVX2 with fused multiply-adds where the
// processor has them) and the dispatcher, against a dense solve in long
// double of M = Lᵀ·D·L built from the same factor: chains of 1, 7 and 16
// nodes and two branched trees, with as many columns as the Jacobian's
// 2N + 1 (and the padding past them left alone by the first kernel, solved
// as zeros by the second).
#include <catch2/catch.hpp>
#include <flange/math/tree_solve.hpp>

#include "tree_parents.hpp"

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Cholesky>

using namespace flange;

namespace {

using test::chain_parents;
/// Two branches from node 1, one branching again; a second root at node 8.
struct branched_parents {
  static constexpr std::array<int, 11> parent{0, 0, 1, 2, 1, 4, 4, 5, 0, 8, 8};
};
/// Every node on the root.
struct star_parents {
  static constexpr std::array<int, 6> parent{0, 0, 0, 0, 0, 0};
};

using LMat = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

/// A factor with the tree's zeros (L(k, a) ≠ 0 for a = k or an ancestor),
/// as math/tree_solve.hpp holds it (column-major: U = D·L below the
/// diagonal, L above it, transposed; D on it), and the inverses of its
/// pivots D_k.
template <class Tree>
void random_factor(std::mt19937& rng, std::vector<double>& C, std::vector<double>& inv) {
  constexpr int N = Tree::NN - 1;
  std::uniform_real_distribution<double> u(-0.3, 0.3), d(1, 2);
  C.assign(N * N, 0.0);
  inv.assign(N + 1, 0.0);
  for (int k = 1; k <= N; ++k) {
    const double Dk = d(rng);
    C[(k - 1) + (k - 1) * N] = Dk;
    inv[k] = 1 / Dk;
    for (int a = Tree::parent[k]; a != 0; a = Tree::parent[a]) {
      const double L = u(rng);
      C[(a - 1) + (k - 1) * N] = L;
      C[(k - 1) + (a - 1) * N] = Dk * L;
    }
  }
}

/// The largest |X − M⁻¹·B| over X's first cols columns, relative to the
/// largest |M⁻¹·B|, with M = Lᵀ·D·L (L read above C's diagonal, D on it)
/// solved densely in long double.
double solve_error(int N, int cols, int ld, const std::vector<double>& C, const std::vector<double>& B,
                   const std::vector<double>& X) {
  LMat L = LMat::Identity(N, N), D = LMat::Zero(N, N), Bl(N, cols);
  for (int k = 0; k < N; ++k) {
    D(k, k) = C[k + k * N];
    for (int a = 0; a < k; ++a) L(k, a) = C[a + k * N];
  }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) Bl(r, c) = B[r * ld + c];
  const LMat M = L.transpose() * D * L;
  const LMat ref = M.llt().solve(Bl);
  long double worst = 0, scale = ref.cwiseAbs().maxCoeff();
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) worst = std::max(worst, std::abs(X[r * ld + c] - ref(r, c)));
  return double(worst / scale);
}

template <class Parents>
void check_tree(std::mt19937& rng) {
  using Tree = detail::tree_runs<Parents>;
  constexpr int N = Tree::NN - 1, cols = 2 * N + 1, ld = detail::tree_solve_row(cols);
  static_assert(ld % 4 == 0 && ld >= cols && ld < cols + 4);
  std::vector<double> C, inv;
  random_factor<Tree>(rng, C, inv);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> B(N * ld);
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < ld; ++c) B[r * ld + c] = c < cols ? u(rng) : 0.0;
  // The solve's error is a few ε times M's condition number (below 10 here).
  const double tol = 1e-14;
  INFO("N = " << N);
  {
    std::vector<double> X = B;
    // A value past the columns: the first kernel leaves it as it was.
    if (ld > cols) X[ld - 1] = 7;
    detail::tree_solve_blocks<Tree, cols>(C.data(), N, inv.data(), X.data(), ld);
    CHECK(solve_error(N, cols, ld, C, B, X) < tol);
    if (ld > cols) CHECK(X[ld - 1] == 7);
  }
  {
    std::vector<double> X = B;
    detail::tree_solve<Tree, cols>(C.data(), N, inv.data(), X.data());
    CHECK(solve_error(N, cols, ld, C, B, X) < tol);
    for (int r = 0; r < N; ++r)
      for (int c = cols; c < ld; ++c) CHECK(X[r * ld + c] == 0);
  }
  {
    // The first 2N columns alone in rows of ld numbers (the Jacobian's
    // solve where ∂/∂t is zero): those solved, the columns past the next
    // multiple of four left as they were.
    constexpr int first = 2 * N;
    std::vector<double> X = B;
    for (int r = 0; r < N; ++r) X[r * ld + ld - 1] = 7;
    detail::tree_solve<Tree, first, ld>(C.data(), N, inv.data(), X.data());
    CHECK(solve_error(N, first, ld, C, B, X) < tol);
    for (int r = 0; r < N; ++r)
      if (detail::tree_solve_row(first) < ld) CHECK(X[r * ld + ld - 1] == 7);
  }
#ifdef FLANGE_TREE_SOLVE_AVX2
  if (detail::cpu_has_avx2_fma) {
    std::vector<double> X = B;
    detail::tree_solve_avx2<Tree, ld, ld>(C.data(), N, inv.data(), X.data());
    CHECK(solve_error(N, cols, ld, C, B, X) < tol);
  }
#endif
}

}  // namespace

TEST_CASE("tree_solve: both kernels solve a tree's M·X = B as a dense solve in long double does") {
  std::mt19937 rng(11);
  for (int round = 0; round < 5; ++round) {
    check_tree<chain_parents<1>>(rng);
    check_tree<chain_parents<7>>(rng);
    check_tree<chain_parents<16>>(rng);
    check_tree<branched_parents>(rng);
    check_tree<star_parents>(rng);
  }
#ifdef FLANGE_TREE_SOLVE_AVX2
  if (!detail::cpu_has_avx2_fma) WARN("this processor has no AVX2 and FMA: their kernel was not run");
#endif
}

TEST_CASE("tree_solve: a tree's runs name each node's descendants and ancestors once, in node order") {
  using Tree = detail::tree_runs<branched_parents>;
  auto nodes = [](const auto& start, const auto& runs, int k) {
    std::vector<int> r;
    for (int b = start[k]; b < start[k + 1]; ++b)
      for (int x = runs[b].lo; x < runs[b].hi; ++x) r.push_back(x);
    return r;
  };
  // Below node 1: 2 … 7; node 4: 5, 6, 7; node 8: 9, 10; leaves none.
  const std::vector<std::vector<int>> below{{}, {2, 3, 4, 5, 6, 7}, {3}, {}, {5, 6, 7}, {7}, {}, {}, {9, 10}, {}, {}};
  // Above node 7: 5, 4, 1, in two runs (1; 4, 5).
  const std::vector<std::vector<int>> above{{}, {}, {1}, {1, 2}, {1}, {1, 4}, {1, 4}, {1, 4, 5}, {}, {8}, {8}};
  for (int k = 1; k < Tree::NN; ++k) {
    CHECK(nodes(Tree::below_start, Tree::below, k) == below[k]);
    CHECK(nodes(Tree::above_start, Tree::above, k) == above[k]);
  }
  CHECK(Tree::above_start[8] - Tree::above_start[7] == 2);
  // Rows solved in pairs: from the leaves k and k − 1 where k is k − 1's
  // only child (3 of 2 alone: 7 is 5's, not 6's); from the root k and
  // k + 1 where k is k + 1's parent (1, 2, 4, 8).
  const std::array<bool, 11> leaves{false, false, false, true, false, false, false, false, false, false, false};
  const std::array<bool, 11> root{false, true, true, false, true, false, false, false, true, false, false};
  CHECK(Tree::pair_from_leaves == leaves);
  CHECK(Tree::pair_from_root == root);
  // A chain is one run each way.
  using Chain = detail::tree_runs<chain_parents<16>>;
  CHECK(Chain::below.size() == 15);
  CHECK(Chain::above.size() == 15);
  for (int k = 1; k <= 16; ++k) {
    CHECK(Chain::pair_from_leaves[k] == (k >= 2));
    CHECK(Chain::pair_from_root[k] == (k < 16));
  }
}
