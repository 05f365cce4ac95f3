// Time of placing the Jacobian's rows into J's columns alone
// (math/place_transposed.hpp): the portable kernel (four rows a column at a
// time) and the AVX2 one (4 × 4 blocks turned in registers), in turns, on
// the shapes of the benchmark's scenes: chains of 7, 16 and 32 links (rows
// and columns in order) and a floating tree of 4 legs of 4 joints (22 rates,
// rows permuted, a ball's three turn columns left out); beside them, what
// zeroing J's q̇ rows takes (Eigen's topRows<nq>().setZero()). Not part of
// the CMake build:
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -isystem /usr/include/eigen3 tools/probes/place_transposed_kernels.cpp -o /tmp/pt && taskset -c 1 /tmp/pt
//
// Prints the median of 15 rounds of 2000 placements for each, in ns.
#include <flange/math/place_transposed.hpp>

#include "median_ns.hpp"

#include <array>
#include <cstdio>

#include <Eigen/Core>

namespace {

template <int nq, int nv, bool Tree>
void measure(const char* name) {
  constexpr int n = nq + nv, ls = (2 * nv + 1 + 3) / 4 * 4;
  static constexpr std::array<int, nv> row_to = [] {
    std::array<int, nv> r{};
    for (int k = 0; k < nv; ++k) r[k] = Tree ? (k * 7) % nv : k;
    return r;
  }();
  static constexpr std::array<int, 2 * nv> col_to = [] {
    std::array<int, 2 * nv> c{};
    for (int k = 0; k < nv; ++k) c[k] = !Tree ? k : k >= 3 && k < 6 ? -1 : k + 1, c[nv + k] = nq + k;
    return c;
  }();
  alignas(32) static double d[nv * ls];
  static Eigen::Matrix<double, n, n> J;
  for (int i = 0; i < nv * ls; ++i) d[i] = i;
  auto sink = [] { asm volatile("" : : "r"(J.data()) : "memory"); };
  const double portable = median_ns([&] {
    flange::detail::place_transposed_portable<ls, n, row_to, col_to>(d, J.data(), nq);
    sink();
  });
  double avx2 = 0;
#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
  if (flange::detail::cpu_has_avx2)
    avx2 = median_ns([&] {
      flange::detail::place_transposed_avx2<ls, n, row_to, col_to>(d, J.data(), nq);
      sink();
    });
#endif
  const double zero = median_ns([&] {
    J.template topRows<nq>().setZero();
    sink();
  });
  std::printf("%-24s portable_ns=%.1f avx2_ns=%.1f zero_rows_ns=%.1f\n", name, portable, avx2, zero);
}

}  // namespace

int main() {
  measure<7, 7, false>("chain N=7");
  measure<16, 16, false>("chain N=16");
  measure<32, 32, false>("chain N=32");
  measure<23, 22, true>("4 legs of 4 joints");
}
