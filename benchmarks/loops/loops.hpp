// The loops benchmark's harness (benchmarks/loops/): a row of N
// parallelogram windows (models::window_row, N loops, 2N constraint rows),
// checked against its closed form and timed. One line per size:
//
//   loops window_row windows=<n> derivative_ns=<x> projection_ns=<y>
//
// x: the median time of one derivative (the constrained accelerations,
// dynamics/loop_solve.hpp) at a state on the loops; y: of one projection
// (normalize: Newton on Φ, then G·v = 0) of that state with every
// coordinate and rate moved by up to 6e-9, about what an accepted step at
// tolerance 1e-8 leaves. Each size is a translation unit of its own
// (windows.cpp), so that they build in parallel.
#pragma once
#include <flange/flange.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "../rounds.hpp"

namespace loops {

struct row {
  int windows;
  double derivative_ns, projection_ns;
};
struct size_case {
  int windows;
  row (*run)();
};
/// The sizes this build has, each added by its translation unit.
inline std::vector<size_case>& cases() {
  static std::vector<size_case> c;
  return c;
}

using rounds::block_ns;
using rounds::calls_for;
using rounds::median;

[[noreturn]] inline void fail(int windows, const char* what, double got, double limit) {
  std::printf("loops window_row windows=%d: %s %.3g, over %.3g\n", windows, what, got, limit);
  std::exit(1);
}

/// The row of N windows with every post at angle th turning at w, its loops
/// closed; checked against the closed form, then timed.
template <int N>
row window_row_case() {
  using namespace flange;
  const models::window_row_params p{};
  const auto scene = models::window_row<N>(p);
  using S = std::remove_cvref_t<decltype(scene)>;
  const double th = 1.2, w = 0.7;
  typename S::state_type x{};
  for (int i = 0; i <= N; ++i) {
    const int k = S::q_offset("post_pivot" + std::to_string(i));
    x[k] = th;
    x[S::n_q + k] = w;
  }
  for (int i = 0; i < N; ++i) {
    const int k = S::q_offset("top_pin" + std::to_string(i));
    x[k] = -th;
    x[S::n_q + k] = -w;
  }
  close_loops<"post_pivot0">(scene, x);

  // One degree of freedom: the posts turn alike and the top bars translate,
  // so J·θ̈ = −V'(θ) with J = (N+1)·m_p·h²/3 + N·m_t·h² and
  // V = ((N+1)·m_p·h/2 + N·m_t·h)·g·sin θ: θ̈ does not depend on θ̇.
  const double h = p.height, g = -p.g.y();
  const double J = (N + 1) * p.m_post * h * h / 3 + N * p.m_top * h * h;
  const double acc = -((N + 1) * p.m_post * h / 2 + N * p.m_top * h) * g * std::cos(th) / J;
  typename S::state_type dx{};
  scene(x, dx, 0.0);
  auto accel = [&](const std::string& joint) { return dx[S::n_q + S::q_offset(joint)]; };
  double err = 0;
  for (int i = 0; i <= N; ++i) err = std::max(err, std::abs(accel("post_pivot" + std::to_string(i)) - acc));
  for (int i = 0; i < N; ++i) err = std::max(err, std::abs(accel("top_pin" + std::to_string(i)) + acc));
  // The solve's round-off: a few ε times its condition (2.6e-15 of |θ̈| at
  // 2 windows, 7.3e-15 at 40).
  const double limit = 1e-12 * std::abs(acc);
  if (!(err <= limit)) fail(N, "the derivative differs from the closed form θ̈ by", err, limit);

  auto off = x;
  for (int i = 0; i < S::n_q + S::n_v; ++i) off[i] += 1e-9 * double((i * 7919) % 13 - 6);
  auto y = off;
  normalize(scene, y);
  const auto left = loop_residual(scene, y);
  if (!(left.max_phi() <= 1e-12 && left.max_phid() <= 1e-12))
    fail(N, "the projection leaves max |Φ|, |G·v| of", std::max(left.max_phi(), left.max_phid()), 1e-12);

  auto f = [&] {
    asm volatile("" : : "r"(x.data()) : "memory");
    scene(x, dx, 0.0);
    asm volatile("" : : "r"(dx.data()) : "memory");
  };
  auto q = [&] {
    y = off;
    asm volatile("" : : "r"(y.data()) : "memory");
    normalize(scene, y);
    asm volatile("" : : "r"(y.data()) : "memory");
  };
  const long nf = calls_for(f), nq = calls_for(q);
  std::vector<double> tf, tq;
  for (int r = 0; r < 15; ++r) {
    tf.push_back(block_ns(f, nf));
    tq.push_back(block_ns(q, nq));
  }
  const row out{N, median(tf), median(tq)};
  std::printf("loops window_row windows=%d derivative_ns=%.0f projection_ns=%.0f\n", N, out.derivative_ns,
              out.projection_ns);
  std::fflush(stdout);
  return out;
}

}  // namespace loops
