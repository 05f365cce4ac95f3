// Time of the Jacobian's two solves alone: M·X = B for a chain's mass matrix
// and the 2N + 1 right-hand sides of ∂v̇/∂x, by the triangular solves of M's
// leaves-first Cholesky factor (math/tree_solve.hpp, its AVX2 kernel) and by
// M's articulated-body factor (math/chain_solve.hpp, its AVX2 kernel and
// Eigen's rows), in turns, in space (six numbers a node) and in the
// plane (three). Not part of the CMake build:
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -isystem /usr/include/eigen3 tools/probes/chain_solve_kernels.cpp -o /tmp/cs && taskset -c 1 /tmp/cs
//
// Prints, for N = 7, 16, 32 and 64, the median of 15 rounds of 2000 solves
// for each in ns per solve (the copy of B that starts each solve included; X
// on a 32-byte boundary; factors excluded), and the largest difference
// between the two AVX2 kernels' results relative to the largest entry.
#include <flange/math/chain_solve.hpp>
#include <flange/math/tree_solve.hpp>

#include "../../tests/tree_parents.hpp"
#include "median_ns.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using flange::test::chain_parents;

template <int N, int C>
void run() {
  using Tree = flange::detail::tree_runs<chain_parents<N>>;
  using Mat = Eigen::Matrix<double, C, C>;
  using Vec = Eigen::Matrix<double, C, 1>;
  constexpr int cols = 2 * N + 1, row = flange::detail::tree_solve_row(cols);
  // A chain: columns and own inertias (symmetric, positive definite).
  std::array<std::array<double, C>, N> s;
  std::array<Mat, N> A;
  for (int k = 0; k < N; ++k) {
    Mat G;
    for (int i = 0; i < C; ++i) {
      s[k][i] = std::sin(1.1 * k + 0.7 * i + 0.3);
      for (int j = 0; j < C; ++j) G(i, j) = std::cos(0.9 * k + 1.3 * i + 0.5 * j);
    }
    A[k] = G * G.transpose() + 0.5 * Mat::Identity();
  }
  // M and its leaves-first Cholesky factor (column-major), as
  // dynamics/derivatives.hpp forms them.
  std::vector<Mat> Ic(N);
  Ic[N - 1] = A[N - 1];
  for (int k = N - 2; k >= 0; --k) Ic[k] = A[k] + Ic[k + 1];
  std::vector<double> F(N * N, 0.0), inv(N + 1), diag(N), B(N * row, 0.0);
  auto col = [&](int k) { return Eigen::Map<const Vec>(s[k].data()); };
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= i; ++j) F[i + j * N] = col(i).dot(Ic[i] * col(j));
  for (int k = 0; k < N; ++k) diag[k] = F[k + k * N];
  for (int k = N - 1; k >= 0; --k) {
    const double d = std::sqrt(F[k + k * N]);
    F[k + k * N] = d;
    inv[k + 1] = 1 / d;
    for (int i = 0; i < k; ++i) F[k + i * N] /= d;
    for (int j = 0; j < k; ++j)
      for (int i = j; i < k; ++i) F[i + j * N] -= F[k + i * N] * F[k + j * N];
  }
  flange::detail::chain_factor<N, C> f;
  if (!f.factor(s, [&](int k) { return A[k]; }, diag.data(), 1e-12)) std::printf("a pivot failed\n");
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) B[r * row + c] = std::cos(0.9 * r + 0.4 * c);
  alignas(32) static std::array<double, N * row> X, Y, Z;
  auto timed = [&](std::array<double, N * row>& out, auto solve) {
    return median_ns([&] {
      std::copy(B.begin(), B.end(), out.begin());
      double* x = out.data();
      asm volatile("" : "+r"(x));  // an address the kernel does not know, as in flange
      solve(x);
    });
  };
  const double rows = timed(Z, [&](double* x) { flange::detail::chain_solve_blocks<N, C, cols>(f, x, row); });
  double tree = 0, chain = 0, diff = 0;
#if defined(FLANGE_TREE_SOLVE_AVX2) && defined(FLANGE_CHAIN_SOLVE_AVX2)
  if (flange::detail::cpu_has_avx2_fma) {
    tree = timed(X, [&](double* x) { flange::detail::tree_solve_avx2<Tree, row, row>(F.data(), N, inv.data(), x); });
    chain = timed(Y, [&](double* x) { flange::detail::chain_solve_avx2<N, C, row, row>(f, x); });
    double scale = 0;
    for (int i = 0; i < N * row; ++i) {
      diff = std::max(diff, std::abs(X[i] - Y[i]));
      scale = std::max(scale, std::abs(X[i]));
    }
    diff /= scale;
  }
#endif
  std::printf("chain_solve N=%d C=%d columns=%d cholesky_avx2_ns=%.0f articulated_avx2_ns=%.0f ratio=%.2f "
              "articulated_rows_ns=%.0f max_difference=%.1e\n",
              N, C, cols, tree, chain, chain > 0 ? tree / chain : 0.0, rows, diff);
}

}  // namespace

int main() {
  run<7, 6>();
  run<16, 6>();
  run<32, 6>();
  run<64, 6>();
  run<7, 3>();
  run<16, 3>();
  run<32, 3>();
}
