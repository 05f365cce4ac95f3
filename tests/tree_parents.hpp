// Trees by their parents, as math/tree_solve.hpp's tree_runs reads them
// (tree_solve_test.cpp, tools/probes/tree_solve_kernels.cpp).
#pragma once
#include <array>

namespace flange::test {

/// A chain of N nodes: node k's parent is k − 1.
template <int N>
struct chain_parents {
  static constexpr std::array<int, N + 1> parent = [] {
    std::array<int, N + 1> p{};
    for (int k = 1; k <= N; ++k) p[k] = k - 1;
    return p;
  }();
};

}  // namespace flange::test
