// The Jacobian benchmark's measurement (jacobian.cpp lists the scenes): the
// derivative, jacobian() and, in the full build, jacobian_dual() timed in
// turns in one process, medians of 15 rounds, one line per scene:
//
//   jacobian <scene> N=<n> derivative_ns=<x> jacobian_ns=<y> ratio=<y/x> [dual_ns=<z>] [analytic_ns=<w>] path=<analytic|implicit|dual>
//
// analytic_ns: for a scene the analytic derivatives cover but jacobian()
// takes dual numbers for (one rate, or one link with force elements), their
// time.
// implicit: a scene with loops, differentiated through its constrained
// system where the loop solve is exact at x (detail::jacobian_loops).
#pragma once
#include <algorithm>
#include <cstdio>
#include <vector>

#include <flange/simulate/jacobian.hpp>

#include "../rounds.hpp"

namespace jacobian_bench {

/// Scenes whose jacobian() and jacobian_dual() differ beyond round-off.
inline int failures = 0;

/// The -DFLANGE_SCALE_FULL=ON build: it also times jacobian_dual() where its
/// units cost minutes to compile.
#ifdef FLANGE_SCALE_FULL
inline constexpr bool full = true;
#else
inline constexpr bool full = false;
#endif

/// Times scene S at state x; WithDual adds jacobian_dual()'s figure (and
/// first checks that jacobian() equals it to 1e-12 of the largest entry).
template <bool WithDual, class S, class State>
void measure(const char* name, int n, const S& s, State x) {
  constexpr bool analytic = flange::detail::jacobian_takes_analytic<S>();
  bool implicit = false;
  if constexpr (flange::detail::has_loops<S>) {
    flange::jacobian_matrix<S> J;
    implicit = flange::detail::jacobian_loops(s, 0.0, x, J);
  }
  if constexpr (WithDual && (analytic || flange::detail::has_loops<S>)) {
    const auto J = flange::jacobian(s, 0.0, x), Jd = flange::jacobian_dual(s, 0.0, x);
    if ((J - Jd).cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, Jd.cwiseAbs().maxCoeff())) {
      std::printf("jacobian %s N=%d differs from the dual-number Jacobian\n", name, n);
      ++failures;
    }
  }
  typename S::state_type f;
  double sink = 0;
  // Each call sees a new state (q[0] moves by ±1e-12 in turn), so nothing is
  // hoisted, and a loop scene's state stays on its loop to round-off.
  double step = 1e-12;
  auto nudge = [&] {
    x[0] += step;
    step = -step;
  };
  auto derivative = [&] {
    s(x, f, 0.0);
    sink += f[S::n_state - 1];
    nudge();
  };
  auto fast = [&] {
    sink += flange::jacobian(s, 0.0, x)(S::n_state - 1, 0);
    nudge();
  };
  auto dual = [&] {
    if constexpr (WithDual) sink += flange::jacobian_dual(s, 0.0, x)(S::n_state - 1, 0);
    nudge();
  };
  constexpr bool other = WithDual && !analytic && flange::detail::analytic_derivatives<S>();
  auto passes = [&] {
    if constexpr (other) sink += flange::detail::jacobian_analytic(s, 0.0, x)(S::n_state - 1, 0);
    nudge();
  };
  const long nd = rounds::calls_for(derivative), nj = rounds::calls_for(fast),
             nu = WithDual ? rounds::calls_for(dual) : 1, na = other ? rounds::calls_for(passes) : 1;
  std::vector<double> td, tj, tu, ta;
  for (int r = 0; r < 15; ++r) {
    td.push_back(rounds::block_ns(derivative, nd));
    tj.push_back(rounds::block_ns(fast, nj));
    if (WithDual) tu.push_back(rounds::block_ns(dual, nu));
    if (other) ta.push_back(rounds::block_ns(passes, na));
  }
  const double d = rounds::median(td), j = rounds::median(tj);
  const char* path = analytic ? "analytic" : implicit ? "implicit" : "dual";
  if (other)
    std::printf("jacobian %s N=%d derivative_ns=%.1f jacobian_ns=%.1f ratio=%.2f dual_ns=%.1f analytic_ns=%.1f path=%s\n",
                name, n, d, j, j / d, rounds::median(tu), rounds::median(ta), path);
  else if (WithDual)
    std::printf("jacobian %s N=%d derivative_ns=%.1f jacobian_ns=%.1f ratio=%.2f dual_ns=%.1f path=%s\n", name, n, d, j,
                j / d, rounds::median(tu), path);
  else
    std::printf("jacobian %s N=%d derivative_ns=%.1f jacobian_ns=%.1f ratio=%.2f path=%s\n", name, n, d, j, j / d, path);
  std::fflush(stdout);
  if (sink == 0.123) std::printf("\n");
}

void chains();
void named_scenes();
void trees();
void large_trees();

}  // namespace jacobian_bench
