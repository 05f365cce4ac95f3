// The Jacobian's cost against one derivative of the same scene (docs/performance.md,
// "The Jacobian"):
//
//   build/benchmarks/jacobian
//
// For each scene, the derivative, jacobian() and (with -DFLANGE_SCALE_FULL=ON,
// up to 16 joints) jacobian_dual() are timed in turns in one process, medians of 15 rounds:
//
//   jacobian <scene> N=<n> derivative_ns=<x> jacobian_ns=<y> ratio=<y/x> [dual_ns=<z>]
//
// Scenes: random chains with run-time axes (chain_any) and with typed
// z axes (chain_z, planar), N = 1 … 16 and 32; 64 with -DFLANGE_SCALE_FULL=ON.
// tests/jacobian_analytic_test.cpp holds jacobian() to jacobian_dual().
// Each scene with the dual figure is first checked: jacobian() against
// jacobian_dual() (1e-12 relative); the program fails if they differ.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <flange/models/chain.hpp>
#include <flange/simulate/jacobian.hpp>

#include "../rounds.hpp"

using namespace flange;

namespace {
int failures = 0;

template <int N, template <int> class Axes>
void run(const char* name) {
  std::mt19937 rng(N);
  const auto p = models::random_chain_params<N>(rng);
  const auto s = models::chain<N, Axes>(p);
  using S = decltype(s);
  std::array<double, S::n_state> x, f;
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& e : x) e = u(rng);
#ifdef FLANGE_SCALE_FULL
  constexpr bool with_dual = N <= 16;
#else
  constexpr bool with_dual = false;  // the dual-number Jacobians cost this unit two minutes to compile
#endif
  if constexpr (with_dual) {
    const auto J = jacobian(s, 0.0, x), Jd = jacobian_dual(s, 0.0, x);
    if ((J - Jd).cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, Jd.cwiseAbs().maxCoeff())) {
      std::printf("jacobian %s N=%d differs from the dual-number Jacobian\n", name, N);
      ++failures;
    }
  }
  double sink = 0;
  // Each call sees a new state (x[0] moves by 1e-12), so nothing is hoisted.
  auto derivative = [&] {
    s(x, f, 0.0);
    sink += f[S::n_state - 1];
    x[0] += 1e-12;
  };
  auto analytic = [&] {
    sink += jacobian(s, 0.0, x)(S::n_state - 1, 0);
    x[0] += 1e-12;
  };
  auto dual = [&] {
    if constexpr (with_dual) sink += jacobian_dual(s, 0.0, x)(S::n_state - 1, 0);
    x[0] += 1e-12;
  };
  const long nd = rounds::calls_for(derivative), nj = rounds::calls_for(analytic),
             nu = with_dual ? rounds::calls_for(dual) : 1;
  std::vector<double> td, tj, tu;
  for (int r = 0; r < 15; ++r) {
    td.push_back(rounds::block_ns(derivative, nd));
    tj.push_back(rounds::block_ns(analytic, nj));
    if (with_dual) tu.push_back(rounds::block_ns(dual, nu));
  }
  const double d = rounds::median(td), j = rounds::median(tj);
  if (with_dual)
    std::printf("jacobian %s N=%d derivative_ns=%.1f jacobian_ns=%.1f ratio=%.2f dual_ns=%.1f\n", name, N, d, j, j / d,
                rounds::median(tu));
  else
    std::printf("jacobian %s N=%d derivative_ns=%.1f jacobian_ns=%.1f ratio=%.2f\n", name, N, d, j, j / d);
  std::fflush(stdout);
  if (sink == 0.123) std::printf("\n");
}
}  // namespace

int main() {
  run<1, models::runtime_axes>("chain_any");
  run<2, models::runtime_axes>("chain_any");
  run<4, models::runtime_axes>("chain_any");
  run<7, models::runtime_axes>("chain_any");
  run<16, models::runtime_axes>("chain_any");
  run<32, models::runtime_axes>("chain_any");
#ifdef FLANGE_SCALE_FULL
  run<64, models::runtime_axes>("chain_any");
#endif
  run<2, models::planar_axes>("chain_z");
  run<4, models::planar_axes>("chain_z");
  run<16, models::planar_axes>("chain_z");
  return failures == 0 ? 0 : 1;
}
