// The loops' constrained accelerations and the projection onto their
// constraints (the constraints themselves: loops.hpp).
//
// The accelerations (forward_dynamics.hpp) solve
//
//   M·v̇ + b = τ + Gᵀ·λ,   G·v̇ = −Ġ·v
//
// by the least change of the tree's accelerations y = M⁻¹·(τ − b) in the
// kinetic-energy norm, on a QR of B = W⁻¹·Gᵀ (M = W·Wᵀ) whose divisions are
// damped where a row vanishes or repeats others: a singular position (a
// parallelogram four-bar lined up) is passed without dividing by zero
// (constrained_accelerations, docs/loops.md).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <type_traits>

#include "flange/detail/inline.hpp"
#include "flange/detail/mask.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/loops.hpp"
#include "flange/dynamics/mass_matrix.hpp"
#include "flange/dynamics/sparse_qr.hpp"
#include "flange/math/dual.hpp"

namespace flange::detail {

/// The scene's size: the largest distance of a frame from its link's origin.
template <class S>
double characteristic_length(const S& scene) {
  return scene.model().length;
}
/// A length scale for the projection's tolerance: the scene's size, at least 1 m.
template <class S>
double length_scale(const S& scene) {
  return std::max(1.0, characteristic_length(scene));
}

/// 1/L for a translation row (metres), 1 for a rotation row: G's rows made
/// comparable, to tell a row that vanishes (a singular position) from one
/// that is merely small in its units.
template <class S>
std::array<double, n_constraints<S>()> row_units(const S& scene) {
  std::array<double, n_constraints<S>()> u{};
  const double inv_L = 1 / characteristic_length(scene);
  for_cuts<S>([&](auto k) {
    using CI = cut_info<S, decltype(k)::value>;
    constexpr int r0 = cut_row<S, decltype(k)::value>();
    for (int i = 0; i < CI::rows; ++i) u[r0 + i] = i < CI::translation_rows ? inv_L : 1.0;
  });
  return u;
}

/// Pivots of G·M⁻¹·Gᵀ (or G·Gᵀ) at or below this fraction of the largest
/// diagonal entry are left out: directions where the constraints are
/// redundant at this position. Round-off in a kept pivot is amplified by at
/// most 1/tolerance, so λ keeps about six digits next to a singular position.
inline constexpr double constraint_pivot_tolerance = 1e-10;

/// Solves A·x = b for a symmetric positive-semidefinite A by LDLᵀ with
/// diagonal pivoting, stopping at the first pivot at or below
/// constraint_pivot_tolerance times A's largest diagonal entry: the rest of
/// x is zero. When b is in A's range the result solves A·x = b. Returns the
/// rank found. A is overwritten.
template <int M, class T>
int solve_semidefinite(Eigen::Matrix<T, M, M>& A, const T* b, T* x) {
  std::array<int, M> p;
  T amax(0);
  for (int i = 0; i < M; ++i) {
    p[i] = i;
    if (A(i, i) > amax) amax = A(i, i);
  }
  Eigen::Matrix<T, M, M> L;
  std::array<T, M> d;
  int rank = 0;
  for (int j = 0; j < M; ++j) {
    int best = j;
    for (int i = j + 1; i < M; ++i)
      if (A(p[i], p[i]) > A(p[best], p[best])) best = i;
    std::swap(p[j], p[best]);
    const T dj = A(p[j], p[j]);
    if (!(dj > T(constraint_pivot_tolerance) * amax)) break;
    d[j] = dj;
    rank = j + 1;
    // L's rows are kept by original index, so that later swaps of p do not move them.
    for (int i = j + 1; i < M; ++i) L(p[i], j) = A(p[i], p[j]) / dj;
    // The update only where L's column is not exactly zero (elsewhere it
    // subtracts zeros): constraints that share no joints leave A sparse.
    std::array<int, M> nz;
    int count = 0;
    for (int i = j + 1; i < M; ++i)
      if (L(p[i], j) != T(0)) nz[count++] = p[i];
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b) A(nz[a], nz[b]) -= L(nz[a], j) * L(nz[b], j) * dj;
  }
  std::array<T, M> c;
  for (int i = 0; i < rank; ++i) {
    c[i] = b[p[i]];
    for (int k = 0; k < i; ++k) c[i] -= L(p[i], k) * c[k];
  }
  for (int i = 0; i < rank; ++i) c[i] /= d[i];
  for (int i = rank - 1; i >= 0; --i)
    for (int k = i + 1; k < rank; ++k) c[i] -= L(p[k], i) * c[k];
  for (int i = 0; i < M; ++i) x[p[i]] = i < rank ? c[i] : T(0);
  return rank;
}

/// The constraint solve's damping μ, relative to each column's own norm
/// ‖B_c‖ (so R_jj/‖B_c‖ measures how far row c is from depending on the
/// rows before it, whatever the masses and units), and its refinement
/// sweeps: each sweep shrinks a direction's error by μ²/(R_jj²/‖B_c‖² + μ²),
/// so at a regular position (R_jj ≳ 0.05·‖B_c‖) four sweeps reach 1e-10,
/// while a direction whose R_jj vanishes (a singular position) stays bounded.
/// Chosen by measurement (docs/loops.md): the parallelogram four-bar through
/// 78 flat positions, and the regular four-bar's energy.
inline constexpr double constraint_damping = 3e-3;
inline constexpr int constraint_sweeps = 4;
/// The sweeps are skipped, for one undamped triangular solve, where every
/// direction's damping leaves out at most this fraction of it (R_jj ≥
/// 100·μ·‖B_c‖): four sweeps would reach that solve to (1e-4)⁴ = 1e-16.
inline constexpr double constraint_sweep_skip = 1e-4;

/// A row of B repeats the rows before it (the constraints are redundant:
/// Bricard's linkage, a planar loop written with run-time axes, the
/// symmetric legs of a parallel mechanism) when its part independent of
/// them is at most constraint_redundancy times the state's drift off the
/// constraints (max |Φ_i|, rows in comparable units), or
/// constraint_redundancy_floor, of its own norm; it is then left out of the
/// solve. On the constraints such a row is a combination of the others; off
/// them its remainder grows with the drift (on Bricard's linkage at most
/// 0.5 times it, and 1e-16 at no drift) and points nowhere in particular: a
/// row kept and damped pulled the accelerations along that noise, and the
/// steps collapsed. A row that is not redundant but vanishes at, or nears, a
/// singular position keeps its own direction and a remainder that does not
/// shrink with the drift (the parallelogram four-bar through its flat
/// positions: 0.64 of its norm and up), and is damped as below. A fixed
/// threshold does not tell them apart: at 1e-3 Bricard's linkage with a
/// seventh joint (cut at j1), which is not redundant, had a real row
/// dropped near a singular position and gained 0.3 % of its energy without
/// an error (docs/loops.md, "Redundant constraints").
inline constexpr double constraint_redundancy = 100;
inline constexpr double constraint_redundancy_floor = 1e-10;

/// The rates from which constrained_accelerations tracks which rows of B's
/// columns can be nonzero and finds R by Givens rotations (where M's factor
/// is sparse), and the projection finds G's nonzeros: below, the dense
/// loops cost less than finding the ones to visit.
inline constexpr int sparse_columns_from = 16;

/// The rates a row of cut K's constraints can be nonzero on (g: the joints
/// from its two frames to the World), and those its column of B = L⁻¹·Gᵀ
/// can be nonzero on (b: and the rates L joins to them, mass_factor<S>),
/// known at compile time.
template <class S, int K>
struct cut_rates {
  /// Marks the rates of the joints from link to the World.
  static constexpr void mark(int link, std::array<bool, S::n_v>& r) {
    for (int L = link; L > 0; L = S::tree.link_parent[L]) {
      const int j = S::tree.link_joint[L];
      for (int k = 0; k < S::table.nv[j]; ++k) r[S::tree.v_offset[j] + k] = true;
    }
  }
  static constexpr std::array<bool, S::n_v> g_mask = [] {
    std::array<bool, S::n_v> r{};
    mark(cut_info<S, K>::link_a, r);
    mark(cut_info<S, K>::link_b, r);
    return r;
  }();
  static constexpr std::array<bool, S::n_v> b_mask = [] {
    if constexpr (mass_factor<S>::sparse) return forward_reach<mass_factor<S>>(g_mask);
    else return std::array<bool, S::n_v>{};  // not used: the dense solve visits every row
  }();
  static constexpr auto g = indices_of<g_mask>();
  static constexpr auto b = indices_of<b_mask>();
  static constexpr rows_mask<S::n_v> b_bits = [] {
    rows_mask<S::n_v> r{};
    for (int i : b) r[i / 64] |= std::uint64_t(1) << (i % 64);
    return r;
  }();
};

/// constrained_accelerations (below) where M's factor and B's columns are
/// sparse: the same least change, with R from Givens rotations of B's rows
/// in the constraints' order (sparse_qr.hpp) instead of Gram–Schmidt with
/// pivoting, so that neither Q nor R fills in: Q·w = B·R⁻¹·w and
/// Qᵀ·Wᵀ·y = R⁻ᵀ·(G·y), each a sparse product and a triangular solve over
/// R's envelope. A row whose remainder is a repeat (constraint_redundancy)
/// is left out and R built again without it.
template <int n, int m, class MM, class F, class T>
void sparse_constrained_accelerations(const MM& Mf, F factor, const std::array<T, n>& wt, const std::array<T, n>& t,
                                      const std::array<std::array<T, n>, m>& B,
                                      const std::array<rows_mask<n>, m>& support, const std::array<T, m>& gamma,
                                      const std::array<T, m>& norm2, const std::array<T, m>& own, T largest,
                                      T repeats, T* vdot, T* lambda, bool* exact) {
  using std::sqrt;
  // B's rows: for each rate, the constraints whose columns can be nonzero in it.
  std::array<rows_mask<m>, n> touches{};
  for (int c = 0; c < m; ++c)
    for_rows(support[c], [&](int i) FLANGE_INLINE_LAMBDA { touches[i][c / 64] |= std::uint64_t(1) << (c % 64); });
  std::array<T, n> sw;  // B's rows are weighted by √D⁻¹
  for (int i = 0; i < n; ++i) sw[i] = sqrt(wt[i]);
  // A row whose remainder repeats the rows before it is left out.
  givens_r<m, T> R;
  R.factor_rows(
      touches, [&](int c, int i) FLANGE_INLINE_LAMBDA { return sw[i] * B[c][i]; },
      [&](int j, const T& rjj) FLANGE_INLINE_LAMBDA {
        const T r2 = rjj * rjj;
        return !(r2 > repeats * norm2[j] && r2 > T(1e-30) * largest);
      });
  // u from Rᵀ·u = γ, damped as in constrained_accelerations.
  std::array<T, m> u{}, inv;
  T e_max(0);
  for (int j = 0; j < m; ++j) {
    if (!R.has(j)) continue;
    const T rjj = R(j, j), mu2 = T(constraint_damping * constraint_damping) * own[j];
    const T den = T(1) / (rjj * rjj + mu2);
    inv[j] = rjj * den;
    const T e = mu2 * den;
    if (e > e_max) e_max = e;
  }
  if (exact) {
    bool all = true;
    for (int j = 0; j < m; ++j) all = all && R.has(j);
    *exact = all && e_max <= T(constraint_sweep_skip);
  }
  if (e_max <= T(constraint_sweep_skip)) {
    R.solve_transposed(gamma.data(), u.data());
  } else {
    std::array<T, m> res, du;
    for (int sweep = 0; sweep < constraint_sweeps; ++sweep) {
      for (int j = 0; j < m; ++j) {  // res = γ − Rᵀ·u
        if (!R.has(j)) continue;
        T x = gamma[j];
        for (int i = R.lo[j]; i <= j; ++i) x -= R.above(i, j) * u[i];
        res[j] = x;
      }
      for (int j = 0; j < m; ++j) {  // Rᵀ·du = res, each division damped
        if (!R.has(j)) {
          du[j] = T(0);
          continue;
        }
        T x = res[j];
        for (int i = R.lo[j]; i < j; ++i) x -= R.above(i, j) * du[i];
        du[j] = x * inv[j];
      }
      for (int j = 0; j < m; ++j) u[j] += du[j];
    }
  }
  // w = u − R⁻ᵀ·(G·y), with G·y = Bᵀ·Wᵀ·y = (L⁻¹·Gᵀ)ᵀ·t.
  std::array<T, m> gy, qy, w, x;
  for (int c = 0; c < m; ++c) {
    T d(0);
    for_rows(support[c], [&](int i) FLANGE_INLINE_LAMBDA { d += B[c][i] * t[i]; });
    gy[c] = d;
  }
  R.solve_transposed(gy.data(), qy.data());
  for (int j = 0; j < m; ++j) w[j] = u[j] - qy[j];
  // x = R⁻¹·w: the constraint forces, and Q·w = B·x.
  R.solve(w.data(), x.data());
  if (lambda)
    for (int c = 0; c < m; ++c) lambda[c] = x[c];
  std::array<T, n> dz;
  for (int i = 0; i < n; ++i) dz[i] = T(0);
  for (int c = 0; c < m; ++c) {
    if (!R.has(c)) continue;
    for_rows(support[c], [&](int i) FLANGE_INLINE_LAMBDA { dz[i] += x[c] * B[c][i]; });
  }
  for (int i = 0; i < n; ++i) dz[i] = t[i] + wt[i] * dz[i];
  ldlt_backward<n>(Mf, dz.data(), vdot, factor);
}

/// v̇ for the constrained equations of motion, given the factors of M
/// (ldlt.hpp) and r = τ − b.
///
/// With M = W·Wᵀ (W = L·√D) and z = Wᵀ·v̇, the accelerations are the least
/// change ‖z − Wᵀ·y‖ of the tree's y = M⁻¹·r with Bᵀ·z = γ = −Ġ·v,
/// B = W⁻¹·Gᵀ. Modified Gram–Schmidt with column pivoting gives B·P = Q·R,
/// and z = Wᵀ·y + Q·w with R₁₁ᵀ·(Qᵀ·Wᵀ·y + w) = (Pᵀ·γ): v̇ = y + W⁻ᵀ·Q·w.
/// The triangular solve divides by R_jj damped, R_jj / (R_jj² + μ²),
/// refined by a few sweeps: a direction in which the constraints are
/// (nearly) redundant, at a singular position, is not divided by its
/// vanishing R_jj. Working on B rather than on G·M⁻¹·Gᵀ = Bᵀ·B keeps the
/// conditioning to cond(B).
///
/// B's columns are kept as L⁻¹·Gᵀ (B = D^(−1/2)·L⁻¹·Gᵀ) with the inner
/// product weighted by D⁻¹, which is B's own: no square root of D, and with
/// t = D⁻¹·L⁻¹·r (so that y = L⁻ᵀ·t and Wᵀ·y = √D·t), Qᵀ·Wᵀ·y is the
/// unweighted product with t and v̇ = L⁻ᵀ·(t + D⁻¹·Q·w) is one backward
/// substitution. Each division by R_jj is a product with its reciprocal.
/// What is saved is mostly latency: every step of the solve waits on the
/// one before.
///
/// With lambda given, also the constraint forces λ (row by row: Gᵀ·λ is
/// their generalized force), from R₁₁·(Pᵀ·λ) = Qᵀ·(z − Wᵀ·y). With exact
/// given, whether the solve was the exact one: every row kept (none
/// repeats the others) and no division damped, so that v̇ and λ solve
/// M·v̇ + b = τ + Gᵀ·λ, G·v̇ = −Ġ·v to round-off (what the Jacobian's
/// implicit differentiation needs, simulate/jacobian.hpp).
template <class S, class T, class MM, class Motions>
void constrained_accelerations(const S& scene, const Motions& motions, const MM& Mf, const ldlt_pivots<S::n_v, T>& f,
                               const T* v, const T* rhs, T* vdot, T* lambda = nullptr, bool* exact = nullptr) {
  using std::sqrt;
  constexpr int n = S::n_v, m = n_constraints<S>();
  const auto k = loop_kinematics_at<S>(scene, motions, v);
  const auto& wt = f.inv_d;  // the inner product's weights
  std::array<T, n> t;
  ldlt_forward<n>(Mf, rhs, t.data(), mass_factor<S>{});
  for (int i = 0; i < n; ++i) t[i] *= wt[i];
  std::array<std::array<T, n>, m> B;
  std::array<T, m> gamma, norm2;
  std::array<int, m> p;
  // Where M's factor is sparse (a tree with branches that share no joints)
  // B's columns are too: each keeps the rows that can be nonzero (exact
  // zeros left out: a dual number's with its derivatives), and from 16
  // rates on the solve is sparse_constrained_accelerations'.
  constexpr bool sparse = mass_factor<S>::sparse && n >= sparse_columns_from;
  std::array<rows_mask<n>, m> support;
  auto norm_of = [&](int c) FLANGE_INLINE_LAMBDA {
    T s(0);
    if constexpr (sparse) for_rows(support[c], [&](int i) FLANGE_INLINE_LAMBDA { s += wt[i] * B[c][i] * B[c][i]; });
    else
      for (int i = 0; i < n; ++i) s += wt[i] * B[c][i] * B[c][i];
    return s;
  };
  // Each row of G's squared norm, the damping's yardstick (found with B's
  // columns where sparse, below otherwise).
  std::array<T, m> g2;
  if constexpr (sparse) {
    // A cut's rows touch the joints from its two frames to the World, and
    // after L⁻¹ the rows L joins to those (cut_rates): only those are
    // visited.
    for_cuts<S>([&](auto kk) FLANGE_INLINE_LAMBDA {
      constexpr int K = decltype(kk)::value;
      using C = cut_rates<S, K>;
      for (int c = cut_row<S, K>(); c < cut_row<S, K>() + cut_info<S, K>::rows; ++c) {
        B[c].fill(T(0));
        ldlt_forward_on<mass_factor<S>, C::b>(Mf, [&](int i) FLANGE_INLINE_LAMBDA { return k.G(c, i); }, B[c].data());
        support[c] = C::b_bits;
        g2[c] = T(0);
        for (int i : C::g) g2[c] += k.G(c, i) * k.G(c, i);
      }
    });
    for (int c = 0; c < m; ++c) {
      gamma[c] = -k.bias[c];
      norm2[c] = norm_of(c);
    }
  } else {
    for (int c = 0; c < m; ++c) {
      std::array<T, n> g;
      for (int i = 0; i < n; ++i) g[i] = k.G(c, i);
      ldlt_forward<n>(Mf, g.data(), B[c].data(), mass_factor<S>{});
      gamma[c] = -k.bias[c];
      p[c] = c;
      norm2[c] = norm_of(c);
    }
  }
  T largest(0);
  // Each column's damping yardstick: its own squared norm in B, raised by
  // how small its row of G is against the largest (rows in comparable units):
  // a row that vanishes at a singular position is damped, a row that is only
  // small in B because of the masses is not.
  std::array<T, m> own = norm2;
  // How far the state is off the constraints, rows in comparable units: a
  // repeated row's remainder is at most about this (constraint_redundancy).
  T drift(0);
  {
    const auto units = row_units(scene);
    for (int c = 0; c < m; ++c) {
      const T d = k.phi[c] * T(units[c]);
      if (d > drift) drift = d;
      else if (-d > drift) drift = -d;
    }
    T g2max(0);
    for (int c = 0; c < m; ++c) {
      if constexpr (!sparse) {
        g2[c] = T(0);
        for (int i = 0; i < n; ++i) g2[c] += k.G(c, i) * k.G(c, i);
      }
      g2[c] *= T(units[c] * units[c]);
      if (g2[c] > g2max) g2max = g2[c];
    }
    for (int c = 0; c < m; ++c)
      if (g2[c] * T(1e30) > g2max) own[c] = own[c] * g2max / g2[c];
      else own[c] = T(1e300);  // a row of zeros: never divided by
  }
  for (int c = 0; c < m; ++c)
    if (norm2[c] > largest) largest = norm2[c];
  T repeats = T(constraint_redundancy) * drift;  // a remainder at most this fraction of its row's norm: repeated
  if (repeats < T(constraint_redundancy_floor)) repeats = T(constraint_redundancy_floor);
  repeats = repeats * repeats;
  if constexpr (sparse) {
    sparse_constrained_accelerations<n, m>(Mf, mass_factor<S>{}, wt, t, B, support, gamma, norm2, own, largest, repeats,
                                           vdot, lambda, exact);
  } else {
  // Q's columns overwrite B's, in pivot order: a pivot swaps its row of B
  // (and everything kept per row) into place, p[j] remembering the row's
  // original index, and R's columns with it.
  std::array<std::array<T, m>, m> R;
  std::array<T, m> inv_r;
  std::array<T, m> norm2_0 = norm2;
  int rank = 0;
  for (int j = 0; j < m; ++j) {
    int best = -1;
    for (int c = j; c < m; ++c)
      if (norm2[c] > repeats * norm2_0[c] && (best < 0 || norm2[c] > norm2[best])) best = c;
    if (best < 0) break;
    if (best != j) {
      std::swap(B[j], B[best]);
      std::swap(norm2[j], norm2[best]);
      std::swap(norm2_0[j], norm2_0[best]);
      std::swap(own[j], own[best]);
      std::swap(gamma[j], gamma[best]);
      std::swap(p[j], p[best]);
      for (int i = 0; i < j; ++i) std::swap(R[i][j], R[i][best]);
    }
    const T nn = norm2[j];  // B[j]'s squared norm, summed after its last update
    if (!(nn > T(1e-30) * largest)) break;  // exactly dependent: nothing left to damp
    const T r = sqrt(nn);
    R[j][j] = r;
    inv_r[j] = T(1) / r;
    std::array<T, n> bw;  // the weighted column: its products with the others are B's
    for (int i = 0; i < n; ++i) {
      B[j][i] *= inv_r[j];
      bw[i] = wt[i] * B[j][i];
    }
    for (int c = j + 1; c < m; ++c) {
      T d(0);
      for (int i = 0; i < n; ++i) d += bw[i] * B[c][i];
      R[j][c] = d;
      for (int i = 0; i < n; ++i) B[c][i] -= d * B[j][i];
      norm2[c] = norm_of(c);
    }
    rank = j + 1;
  }
  // u = Qᵀ·Wᵀ·y + w from R₁₁ᵀ·u = (Pᵀ·γ)₁.
  // Each direction's damped reciprocal R_jj / (R_jj² + μ²·‖B_c‖²), and how
  // much of R_jj the damping leaves out, e_j = μ²·‖B_c‖² / (R_jj² + μ²·‖B_c‖²):
  // a sweep shrinks direction j's error by about e_j.
  std::array<T, m> u{}, inv;
  T e_max(0);
  for (int j = 0; j < rank; ++j) {
    const T rjj = R[j][j], mu2 = T(constraint_damping * constraint_damping) * own[j];
    const T den = T(1) / (rjj * rjj + mu2);
    inv[j] = rjj * den;
    const T e = mu2 * den;
    if (e > e_max) e_max = e;
  }
  if (exact) *exact = rank == m && e_max <= T(constraint_sweep_skip);
  if (e_max <= T(constraint_sweep_skip)) {
    // Away from singular positions the sweeps converge to R₁₁ᵀ·u = (Pᵀ·γ)₁
    // within round-off (e_max⁴ ≤ 1e-16): solve it once, undamped.
    for (int j = 0; j < rank; ++j) {
      T x = gamma[j];
      for (int i = 0; i < j; ++i) x -= R[i][j] * u[i];
      u[j] = x * inv_r[j];
    }
  } else {
    std::array<T, m> res, du;
    for (int sweep = 0; sweep < constraint_sweeps; ++sweep) {
      for (int j = 0; j < rank; ++j) {  // res = (Pᵀ·γ)₁ − R₁₁ᵀ·u
        T x = gamma[j];
        for (int i = 0; i <= j; ++i) x -= R[i][j] * u[i];
        res[j] = x;
      }
      for (int j = 0; j < rank; ++j) {  // R₁₁ᵀ·du = res, each division damped
        T x = res[j];
        for (int i = 0; i < j; ++i) x -= R[i][j] * du[i];
        du[j] = x * inv[j];
      }
      for (int j = 0; j < rank; ++j) u[j] += du[j];
    }
  }
  std::array<T, n> dz;
  std::array<T, m> w;
  for (int i = 0; i < n; ++i) dz[i] = T(0);
  for (int j = 0; j < rank; ++j) {
    T qz(0);
    for (int i = 0; i < n; ++i) qz += B[j][i] * t[i];
    w[j] = u[j] - qz;
    for (int i = 0; i < n; ++i) dz[i] += w[j] * B[j][i];
  }
  if (lambda) {
    for (int j = m - 1; j >= 0; --j) {
      if (j >= rank) {
        lambda[p[j]] = T(0);
        continue;
      }
      T x = w[j];
      for (int c = j + 1; c < rank; ++c) x -= R[j][c] * lambda[p[c]];
      lambda[p[j]] = x * inv_r[j];
    }
  }
  for (int i = 0; i < n; ++i) dz[i] = t[i] + wt[i] * dz[i];
  ldlt_backward<n>(Mf, dz.data(), vdot, mass_factor<S>{});
  }
}

/// The least change Δv = Gᵀ·(G·Gᵀ)⁺·b, rows of G whose part independent of
/// the rows before them is at or below constraint_pivot_tolerance (squared,
/// against G·Gᵀ's largest diagonal entry) left out: when b is in G's range,
/// G·Δv = b.
///
/// Small (below sparse_columns_from columns): LDLᵀ of G·Gᵀ with diagonal
/// pivoting (Eigen's unrolled product is faster than finding nonzeros).
/// From there on: R of Gᵀ's QR by Givens rotations (sparse_qr.hpp), rows of
/// G in their order, and Δv = Gᵀ·R⁻¹·R⁻ᵀ·b, every product over the entries
/// can_touch says can be nonzero (for each rate, a bit per row of G): constraints that share no joints cost nothing, and a row of
/// loops that share their neighbours' links costs in proportion to its
/// length.
template <int M, int N>
Eigen::Matrix<double, N, 1> least_norm_change(const Eigen::Matrix<double, M, N>& G, const std::array<bool, N>& free,
                                              const std::array<double, M>& b,
                                              const std::array<rows_mask<M>, N>& can_touch) {
  std::array<double, M> mu;
  if constexpr (N < sparse_columns_from) {
    Eigen::Matrix<double, M, N> Gf = G;
    for (int j = 0; j < N; ++j)
      if (!free[j]) Gf.col(j).setZero();
    Eigen::Matrix<double, M, M> A = Gf * Gf.transpose();
    solve_semidefinite<M>(A, b.data(), mu.data());
    return Gf.transpose() * Eigen::Map<const Eigen::Matrix<double, M, 1>>(mu.data());
  } else {
    // Gᵀ's rows: for each free rate, the rows of G that can be nonzero in it.
    std::array<rows_mask<M>, N> touches{};
    double amax = 0;
    {
      std::array<double, M> g2{};
      for (int j = 0; j < N; ++j) {
        if (!free[j]) continue;
        touches[j] = can_touch[j];
        for_rows(touches[j], [&](int c) FLANGE_INLINE_LAMBDA { g2[c] += G(c, j) * G(c, j); });
      }
      for (double e : g2) amax = std::max(amax, e);
    }
    givens_r<M, double> R;
    R.factor_rows(
        touches, [&](int c, int j) FLANGE_INLINE_LAMBDA { return G(c, j); },
        [&](int, double rcc) FLANGE_INLINE_LAMBDA { return !(rcc * rcc > constraint_pivot_tolerance * amax); });
    std::array<double, M> u;
    R.solve_transposed(b.data(), u.data());
    R.solve(u.data(), mu.data());
    Eigen::Matrix<double, N, 1> dv;
    for (int j = 0; j < N; ++j) {
      double s = 0;
      for_rows(touches[j], [&](int c) FLANGE_INLINE_LAMBDA { s += G(c, j) * mu[c]; });
      dv[j] = s;
    }
    return dv;
  }
}

/// The outcome of a projection onto the loops' constraints.
struct closure {
  double phi = 0;        ///< max |Φ_i| left (metres for translation rows, radians for rotation rows)
  double phid = 0;       ///< max |(G·v)_i| left
  int iterations = 0;    ///< Newton steps on Φ
  int worst_row = -1;    ///< the row of the largest |Φ_i|
};

/// The cut whose rows hold constraint row i.
template <class S>
constexpr int cut_of_row(int i) {
  int k = 0;
  [&]<int... K>(std::integer_sequence<int, K...>) {
    ((i >= cut_row<S, K>() && i < cut_row<S, K>() + cut_info<S, K>::rows ? k = K : 0), ...);
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
  return k;
}

/// Cut joints held at given coordinates and rates while the loops close
/// (close_loops, initial_state): for each held cut K..., rows that ask its
/// coordinates, as its frames give them, to be the targets q (angles the
/// short way round) and its rates to be v. Each joint's coordinates are its
/// rates' integrals (nq = nv: not a quaternion).
template <class S, int... K>
struct held_cuts {
  static constexpr int rows = (0 + ... + cut_info<S, K>::joint_type::nv);
  /// Row i's rates that can be nonzero: its cut's (cut_rates).
  static constexpr std::array<std::array<bool, S::n_v>, rows> row_rates = [] {
    std::array<std::array<bool, S::n_v>, rows> r{};
    [[maybe_unused]] int i = 0;
    ((
         [&] {
           for (int k = 0; k < cut_info<S, K>::joint_type::nv; ++k) r[i++] = cut_rates<S, K>::g_mask;
         }()),
     ...);
    return r;
  }();
  std::array<double, rows> q{}, v{};

  /// Row i: its coordinate's distance from the target, and its G row.
  template <class G>
  void add(const S& scene, const double* qs, double* phi, G& g) const {
    std::array<double, S::n_v> zero{};
    const auto motions = link_motions<spatial_algebra, double, true>(scene, qs);
    const auto ls = loop_link_states<S, double>(motions, zero.data());
    int i = 0;
    (
        [&] {
          using CI = cut_info<S, K>;
          using J = typename CI::joint_type;
          const auto a = motion_of_set<S, CI::set_a, double>(scene, ls);
          const auto b = motion_of_set<S, CI::set_b, double>(scene, ls);
          const auto r = read_cut(scene.template component<CI::joint>(), a, b);
          for (int k = 0; k < J::nv; ++k, ++i) {
            const double d = r.q[k] - q[i];
            phi[i] = periodic_coordinates<J>()[k] ? std::remainder(d, 2 * std::numbers::pi) : d;
            std::array<double, S::n_v> row{};
            add_frame_jacobian<S, CI::link_a>(motions, ls.pose, r.rows[k].wa, r.rows[k].va, a.r, row.data());
            add_frame_jacobian<S, CI::link_b>(motions, ls.pose, r.rows[k].wb, r.rows[k].vb, b.r, row.data());
            for (int j = 0; j < S::n_v; ++j) g(i, j) = row[j];
          }
        }(),
        ...);
  }
};

/// For each rate, the rows of the projection's G (the loops', then held's)
/// that can be nonzero on it.
template <class S, class Held>
constexpr auto projection_touches() {
  constexpr int n = S::n_v, mc = n_constraints<S>(), m = mc + Held::rows;
  std::array<rows_mask<m>, n> t{};
  auto add = [&](int c, const std::array<bool, n>& g) {
    for (int j = 0; j < n; ++j)
      if (g[j]) t[j][c / 64] |= std::uint64_t(1) << (c % 64);
  };
  [&]<int... K>(std::integer_sequence<int, K...>) {
    (
        [&] {
          for (int r = 0; r < cut_info<S, K>::rows; ++r) add(cut_row<S, K>() + r, cut_rates<S, K>::g_mask);
        }(),
        ...);
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
  for (int i = 0; i < Held::rows; ++i) add(mc + i, Held::row_rates[i]);
  return t;
}

/// Moves (q, v) onto the loops' constraints, changing only the rates i with
/// free[i] (and their joints' coordinates) and holding the cut joints in
/// held: Newton steps on Φ(q) = 0 (with held's rows), each the least change
/// Δv = G_fᵀ·(G_f·G_fᵀ)⁺·(−Φ) applied through the joints' q̇ (and
/// normalize), until |Φ| stops shrinking or is at round-off; then
/// v ← v + G_fᵀ·(G_f·G_fᵀ)⁺·(−G·v) (held's rates as asked). Reports what is
/// left; the caller judges it.
template <class S, class Held = held_cuts<S>>
closure project_onto_loops(const S& scene, double* q, double* v, const std::array<bool, S::n_v>& free,
                           const Held& held = {}, int max_iterations = 50) {
  constexpr int n = S::n_v, m = n_constraints<S>() + Held::rows;
  closure r;
  if constexpr (m > 0) {
    const double tol = 8 * std::numeric_limits<double>::epsilon() * length_scale(scene);
    std::array<double, n> zero{};
    struct terms {
      std::array<double, m> phi;
      Eigen::Matrix<double, m, n> G;
    };
    // Φ and G of the loops, then held's rows.
    auto terms_at = [&](const double* qs) {
      terms t;
      constexpr int mc = n_constraints<S>();
      if constexpr (mc > 0) {
        const auto k = loop_kinematics<S>(scene, qs, zero.data());
        for (int i = 0; i < mc; ++i) t.phi[i] = k.phi[i];
        t.G.template topRows<mc>() = k.G;
      }
      if constexpr (Held::rows > 0) {
        auto g = t.G.template bottomRows<Held::rows>();
        held.add(scene, qs, t.phi.data() + mc, g);
      }
      return t;
    };
    // Δv = G_fᵀ·(G_f·G_fᵀ)⁺·rhs
    auto least_change = [&](const Eigen::Matrix<double, m, n>& G, const std::array<double, m>& rhs) {
      static constexpr auto can_touch = projection_touches<S, Held>();
      return least_norm_change<m, n>(G, free, rhs, can_touch);
    };
    auto worst = [&](const std::array<double, m>& x, int* row = nullptr) {
      double w = 0;
      for (int i = 0; i < m; ++i)
        if (!(std::abs(x[i]) <= w)) {
          w = std::abs(x[i]);
          if (row) *row = i;
        }
      return w;
    };
    auto norm2 = [](const std::array<double, m>& x) {
      double s = 0;
      for (double e : x) s += e * e;
      return s;
    };
    // Two sets of terms, the accepted one and the trial, swapped by index
    // (no copy of G).
    std::array<terms, 2> buffers;
    int accepted = 0;
    buffers[0] = terms_at(q);
    r.phi = worst(buffers[0].phi, &r.worst_row);
    // Newton with backtracking: a step that does not shrink |Φ| is halved
    // (far from the solution a full step can overshoot), up to 30 times.
    while (r.phi > tol && r.iterations < max_iterations) {
      const terms& k = buffers[accepted];
      std::array<double, m> rhs;
      for (int i = 0; i < m; ++i) rhs[i] = -k.phi[i];
      const auto dv = least_change(k.G, rhs);
      std::array<double, S::n_q> q0;
      std::copy(q, q + S::n_q, q0.begin());
      bool shrank = false;
      for (double alpha = 1; alpha > 1e-9 && !shrank; alpha /= 2) {
        std::copy(q0.begin(), q0.end(), q);
        std::array<double, n> step;
        for (int j = 0; j < n; ++j) step[j] = alpha * dv[j];
        std::array<double, S::n_q> dq{};
        for_links<S>([&](auto l) {
          using LI = link_info<S, decltype(l)::value>;
          const auto& j = scene.template component<LI::joint>();
          j.qdot(q + LI::q, step.data() + LI::v, dq.data() + LI::q);
          for (int i = 0; i < LI::nq; ++i) q[LI::q + i] += dq[LI::q + i];
          normalize_joint(j, q + LI::q);
        });
        terms& kk = buffers[1 - accepted];
        kk = terms_at(q);
        if (norm2(kk.phi) < norm2(k.phi)) {  // the merit is |Φ|₂: Newton's step is a descent direction for it
          shrank = true;
          accepted = 1 - accepted;
          r.phi = worst(kk.phi, &r.worst_row);
        }
      }
      ++r.iterations;
      if (!shrank) {  // a minimum of |Φ| that is not zero: the loop cannot close here
        std::copy(q0.begin(), q0.end(), q);
        break;
      }
    }
    // G·v = 0 on the loops' rows, held's rates as asked on its. (Each
    // gv[i] sums over j in order; G is stored by columns.)
    const terms& k = buffers[accepted];
    std::array<double, m> gv;
    for (int i = 0; i < m; ++i) gv[i] = i < n_constraints<S>() ? 0.0 : held.v[std::max(0, i - n_constraints<S>())];
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) gv[i] -= k.G(i, j) * v[j];
    const auto dv = least_change(k.G, gv);
    for (int j = 0; j < n; ++j) v[j] += dv[j];
    for (int i = 0; i < m; ++i) gv[i] = i < n_constraints<S>() ? 0.0 : -held.v[std::max(0, i - n_constraints<S>())];
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) gv[i] += k.G(i, j) * v[j];
    r.phid = worst(gv);
  }
  return r;
}

}  // namespace flange::detail
