// Time of the Jacobian's solve alone (math/tree_solve.hpp): M·X = B for a
// chain's leaves-first factor and the 2N + 1 right-hand sides of ∂v̇/∂x,
// by Eigen's rows (SSE2 at the project's flags) and by the AVX2 kernel with
// fused multiply-adds, in turns. Not part of the CMake build:
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -isystem /usr/include/eigen3 tools/probes/tree_solve_kernels.cpp -o /tmp/ts && taskset -c 1 /tmp/ts
//
// Prints, for N = 7, 16, 32 and 64, the median of 15 rounds of 2000 solves
// for each kernel in ns per solve (the copy of B that starts each solve
// included; X on a 32-byte boundary), and the largest difference between
// their results.
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

template <int N>
void run() {
  using Tree = flange::detail::tree_runs<chain_parents<N>>;
  constexpr int cols = 2 * N + 1, row = flange::detail::tree_solve_row(cols);
  std::vector<double> C(N * N, 0.0), inv(N + 1), B(N * row, 0.0);
  // On a 32-byte boundary, as simulate/jacobian.hpp places its rows.
  alignas(32) static std::array<double, N * row> X, Y;
  // The factor as math/tree_solve.hpp holds it: D on the diagonal, U = D·L
  // below it, L above it.
  for (int k = 0; k < N; ++k) {
    C[k + k * N] = 1 + 0.1 * k;
    inv[k + 1] = 1 / C[k + k * N];
    for (int a = 0; a < k; ++a) {
      C[a + k * N] = 0.3 * std::sin(1.3 * k + 0.7 * a);
      C[k + a * N] = C[k + k * N] * C[a + k * N];
    }
  }
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < cols; ++c) B[r * row + c] = std::cos(0.9 * r + 0.4 * c);
  const double blocks = median_ns([&] {
    std::copy(B.begin(), B.end(), X.begin());
    double* x = X.data();
    asm volatile("" : "+r"(x));
    flange::detail::tree_solve_blocks<Tree, cols>(C.data(), N, inv.data(), x, row);
  });
  double avx2 = 0, diff = 0;
#ifdef FLANGE_TREE_SOLVE_AVX2
  if (flange::detail::cpu_has_avx2_fma) {
    avx2 = median_ns([&] {
      std::copy(B.begin(), B.end(), Y.begin());
      double* y = Y.data();
      asm volatile("" : "+r"(y));  // an address the kernel does not know, as in flange
      flange::detail::tree_solve_avx2<Tree, row, row>(C.data(), N, inv.data(), y);
    });
    for (int i = 0; i < N * row; ++i) diff = std::max(diff, std::abs(X[i] - Y[i]));
  }
#endif
  std::printf("tree_solve N=%d columns=%d rows_ns=%.0f avx2_ns=%.0f ratio=%.2f max_difference=%.1e\n", N, cols, blocks,
              avx2, avx2 > 0 ? blocks / avx2 : 0.0, diff);
}

}  // namespace

int main() {
  run<7>();
  run<16>();
  run<32>();
  run<64>();
}
