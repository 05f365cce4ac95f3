// The Jacobian benchmark's scenes of the scale benchmark's families and the
// states it measures them at, shared by its units (chains.cpp, trees.cpp, large_trees.cpp)
// and by tools/probes/small_jacobians.cpp, which counts their instructions.
#pragma once
#include <cmath>
#include <random>
#include <utility>

#include <flange/models/chain.hpp>
#include <flange/models/legged.hpp>

namespace jacobian_bench {

/// Typed axes turning x, y, z in turn.
template <int I>
struct xyz_axes {
  using type = flange::axis::coordinate<I % 3>;
};

/// The random chain of N links with axes Axes (seeded by N) and a random
/// state in [−1, 1].
template <int N, template <int> class Axes>
auto random_chain() {
  using namespace flange;
  std::mt19937 rng(N);
  const auto p = models::random_chain_params<N>(rng);
  auto s = models::chain<N, Axes>(p);
  typename decltype(s)::state_type x;
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& e : x) e = u(rng);
  return std::pair{s, x};
}

/// The floating-base tree of Legs legs of Links joints, at its neutral state
/// moved by 0.1·sin(1.3·i + 0.4) in each coordinate i (the quaternion
/// normalized).
template <int Legs, int Links>
auto legged_tree() {
  using namespace flange;
  auto s = models::legged<Legs, Links>();
  auto x = neutral_state(s);
  for (int i = 0; i < decltype(s)::n_state; ++i) x[i] += 0.1 * std::sin(1.3 * i + 0.4);
  normalize(s, x);
  return std::pair{s, x};
}

}  // namespace jacobian_bench
