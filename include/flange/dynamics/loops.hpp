// Closed kinematic loops: the constraints a cut joint puts on the tree.
//
// topology.hpp cuts each loop at a joint (the last joint written in it) and
// leaves that joint out of the tree and of the state. What the cut joint
// would have done becomes constraints on the tree's coordinates: its two
// frames, both placed by the tree, must stay related as the joint allows.
// What a joint leaves free is its as_cut (core/joint.hpp); the rest is
// locked, row by row:
//
//   translations  the origins meet:            d = r_b − r_a = 0        (3 rows)
//                 or only across the axis n:   u_i·d = 0, u_i ⟂ n fixed in frame_a   (2)
//   rotations     frame_b keeps n of frame_a:  u_i·n_b = 0, u_i ⟂ n_a   (2)
//                 or every axis:               e_j,a·e_k,b = 0 for (j, k) = (1, 2), (2, 0), (0, 1)   (3)
//
// A planar scene (every joint's axis the same coordinate axis k, from the
// types: algebra.hpp) keeps only the in-plane rows: a revolute cut gives 2
// rows instead of 5, a prismatic 2, and no row is redundant.
//
// Each row is Φ_i(q) = u·w for two vectors that turn with the frames (or
// with the World); its rate is Φ̇_i = (ω_u × u)·w + u·ẇ exactly: coefficients
// on the two frames' motions. G's row is those coefficients times the motion
// subspaces of the joints between the World and each frame; Ġ·v comes from
// the frames' bias accelerations at v̇ = 0 (the Newton–Euler forward step).
// The coefficients times λ are also the forces the cut joint exerts.
//
// The accelerations (forward_dynamics.hpp) then solve
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
#include <cmath>
#include <concepts>
#include <limits>
#include <string>

#include "flange/detail/inline.hpp"
#include "flange/dynamics/algebra.hpp"
#include "flange/dynamics/kinematics.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/links.hpp"
#include "flange/errors.hpp"
#include "flange/math/dual.hpp"

namespace flange::detail {

/// A joint type that can close a loop: it says what it leaves free, and
/// has no force of its own (a drive or an axis law on a cut joint would act
/// on a coordinate the state does not have).
template <class J>
concept cuttable = requires {
  { J::as_cut } -> std::convertible_to<cut_freedom>;
} && !has_generalized_force<J>;

/// What the dynamics know of cut K at compile time.
template <class S, int K>
struct cut_info {
  static constexpr int joint = S::tree.cuts[K];
  using joint_type = typename S::template component_type<joint>;
  static constexpr bool supported = cuttable<joint_type>;
  static constexpr cut_freedom freedom = [] {
    if constexpr (cuttable<joint_type>) return cut_freedom(joint_type::as_cut);
    else return cut_freedom{3, 3};  // reported by the scene; no rows
  }();
  static constexpr int set_a = S::topology.set_of[S::table.frame_base[joint]];
  static constexpr int set_b = S::topology.set_of[S::table.frame_base[joint] + 1];
  static constexpr int link_a = S::tree.set_link[set_a];
  static constexpr int link_b = S::tree.set_link[set_b];
  /// The plane's normal axis for a planar scene, −1 otherwise.
  static constexpr int plane = planar_axis<S>();
  static constexpr int translation_rows = freedom.translations >= 2 ? 0 : (plane >= 0 ? 2 : 3) - freedom.translations;
  static constexpr int rotation_rows = freedom.rotations >= 2 ? 0
                                       : plane >= 0          ? 1 - freedom.rotations
                                                             : 3 - freedom.rotations;
  static constexpr int rows = translation_rows + rotation_rows;
};

/// The first constraint row of cut K.
template <class S, int K>
constexpr int cut_row() {
  if constexpr (K == 0) return 0;
  else return cut_row<S, K - 1>() + cut_info<S, K - 1>::rows;
}

/// The number of constraint rows of all the scene's loops.
template <class S>
constexpr int n_constraints() {
  return cut_row<S, S::tree.n_cuts>();
}

template <class S>
inline constexpr bool has_loops = S::tree.n_cuts > 0;

/// The first cut whose joint type cannot close a loop (−1: none).
template <class S>
constexpr int first_uncuttable_joint() {
  return []<int... K>(std::integer_sequence<int, K...>) {
    int found = -1;
    ((found < 0 && !cut_info<S, K>::supported ? found = cut_info<S, K>::joint : 0), ...);
    return found;
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
}

/// f(integral_constant<K>) for each cut K.
template <class S, class F>
FLANGE_INLINE void for_cuts(F&& f) {
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, K>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
}

/// A connection set's pose and motion in the world: R rotates world into
/// the set's coordinates; r, its origin's velocity v, ω, and the bias
/// accelerations ω̇ and a (at v̇ = 0, without gravity) are in world
/// coordinates.
template <class T>
struct set_motion {
  Mat3<T> R;
  Vec3<T> r, v, w, wd, a;
};

/// ω̇ and a of every link at v̇ = 0 without gravity (link coordinates): the
/// Newton–Euler forward step (kinematics.hpp) with no rates for v̇.
template <class S, class T, class Motions>
struct bias_pass {
  const Motions& motions;
  const T* v;
  std::array<Vec3<T>, S::tree.n_links>& wd;
  std::array<Vec3<T>, S::tree.n_links>& a;

  template <int L, class K>
  nothing at(const K& k) {
    wd[L] = k.wd.dense();
    a[L] = k.a.dense();
    return {};
  }
  template <int L, int C, class K>
  auto down(const K& k) {
    return forward_step<T>(k, std::get<C - 1>(motions), v + link_info<S, C>::v, no_rates{});
  }
  template <int, int>
  nothing gather(nothing, nothing) {
    return {};
  }
  template <int, class D>
  nothing leave(const D&, nothing) {
    return {};
  }
};

/// The links' world poses and velocities, and their bias accelerations.
template <class S, class T, class Motions>
struct link_states {
  std::array<link_pose<T>, S::tree.n_links> pose;
  std::array<Vec3<T>, S::tree.n_links> wd, a;
};
template <class S, class T, class Motions>
link_states<S, T, Motions> loop_link_states(const Motions& motions, const T* v) {
  link_states<S, T, Motions> r{link_poses<S, T>(motions, v), {}, {}};
  bias_pass<S, T, Motions> ctx{motions, v, r.wd, r.a};
  walk<S, 0>(ctx, link_kinematics{zero_vec<T>{}, zero_vec<T>{}, zero_vec<T>{}});
  return r;
}

template <class S, int Set, class T, class LS>
set_motion<T> motion_of_set(const S& scene, const LS& ls) {
  constexpr int L = S::tree.set_link[Set];
  const link_pose<T>& p = ls.pose[L];
  const Vec3<T> o_l = scene.model().set_offset[Set].template cast<T>();
  const Vec3<T> o = p.R.transpose() * o_l;
  const Vec3<T> w = p.R.transpose() * p.w;
  const Vec3<T> a_l = ls.a[L] + ls.wd[L].cross(o_l) + p.w.cross(p.w.cross(o_l));
  return {Mat3<T>(scene.model().set_rotation[Set].template cast<T>() * p.R),
          p.r + o,
          p.v + w.cross(o),
          w,
          p.R.transpose() * ls.wd[L],
          p.R.transpose() * a_l};
}

/// Two unit vectors that complete the unit n to a right-handed basis (n, e1, e2).
inline void complete_basis(const Vec3d& n, Vec3d& e1, Vec3d& e2) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  e1 = n.cross(Vec3d::Unit(k)).normalized();
  e2 = n.cross(e1);
}

/// One constraint row: Φ, Φ̇, the bias Φ̈ at v̇ = 0 (= Ġ·v), and the row's
/// coefficients on the two frames' motions (world coordinates, at their
/// origins): Φ̇ = wa·ω_a + va·v_a + wb·ω_b + vb·v_b. The same coefficients,
/// times λ, are the torque and force the cut joint exerts on each frame.
template <class T>
struct constraint_row {
  T phi, phid, bias;
  Vec3<T> wa, va, wb, vb;
};

/// A row u·d: u fixed in frame a (u̇ = ω_a × u) or in the World, d = r_b − r_a.
template <class T, bool Turning>
constraint_row<T> translation_row(const Vec3<T>& u, const set_motion<T>& a, const set_motion<T>& b) {
  const Vec3<T> d = b.r - a.r, dd = b.v - a.v, dda = b.a - a.a;
  constraint_row<T> r;
  r.phi = u.dot(d);
  r.va = -u;
  r.vb = u;
  r.wb = Vec3<T>::Zero();
  if constexpr (Turning) {
    const Vec3<T> ud = a.w.cross(u), ux = u.cross(d);
    r.wa = ux;
    r.phid = ud.dot(d) + u.dot(dd);
    r.bias = a.wd.dot(ux) + a.w.dot(ud.cross(d) + u.cross(dd)) + ud.dot(dd) + u.dot(dda);
  } else {
    r.wa = Vec3<T>::Zero();
    r.phid = u.dot(dd);
    r.bias = u.dot(dda);
  }
  return r;
}
/// A row u·w: u fixed in frame a, w fixed in frame b.
template <class T>
constraint_row<T> rotation_row(const Vec3<T>& u, const Vec3<T>& w, const set_motion<T>& a, const set_motion<T>& b) {
  const Vec3<T> wu = w.cross(u), dw = b.w - a.w;
  const Vec3<T> ud = a.w.cross(u), wdot = b.w.cross(w);
  constraint_row<T> r;
  r.phi = u.dot(w);
  r.wa = -wu;
  r.wb = wu;
  r.va = r.vb = Vec3<T>::Zero();
  r.phid = dw.dot(wu);
  r.bias = (b.wd - a.wd).dot(wu) + dw.dot(wdot.cross(u) + w.cross(ud));
  return r;
}

/// Cut K's rows from its two frames' motions.
template <class S, int K, class T>
void cut_constraint(const S& scene, const set_motion<T>& a, const set_motion<T>& b, constraint_row<T>* rows) {
  using CI = cut_info<S, K>;
  const auto& joint = scene.template component<CI::joint>();
  int i = cut_row<S, K>();
  auto in_a = [&](const Vec3d& e) { return Vec3<T>(a.R.transpose() * e.template cast<T>()); };
  auto in_b = [&](const Vec3d& e) { return Vec3<T>(b.R.transpose() * e.template cast<T>()); };
  if constexpr (CI::freedom.translations == 0) {
    for (int c = 0; c < 3; ++c)
      if (c != CI::plane) rows[i++] = translation_row<T, false>(Vec3<T>::Unit(c), a, b);
  } else if constexpr (CI::translation_rows > 0) {
    if constexpr (CI::plane >= 0) {
      rows[i++] = translation_row<T, true>(in_a(Vec3d::Unit(CI::plane).cross(joint.n())), a, b);
    } else {
      Vec3d e1, e2;
      complete_basis(joint.n(), e1, e2);
      rows[i++] = translation_row<T, true>(in_a(e1), a, b);
      rows[i++] = translation_row<T, true>(in_a(e2), a, b);
    }
  }
  if constexpr (CI::rotation_rows > 0) {
    if constexpr (CI::freedom.rotations == 1) {
      Vec3d e1, e2;
      complete_basis(joint.n(), e1, e2);
      const Vec3<T> n = in_b(joint.n());
      rows[i++] = rotation_row<T>(in_a(e1), n, a, b);
      rows[i++] = rotation_row<T>(in_a(e2), n, a, b);
    } else if constexpr (CI::plane >= 0) {
      rows[i++] = rotation_row<T>(in_a(Vec3d::Unit((CI::plane + 1) % 3)), in_b(Vec3d::Unit((CI::plane + 2) % 3)), a, b);
    } else {
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitY()), in_b(Vec3d::UnitZ()), a, b);
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitZ()), in_b(Vec3d::UnitX()), a, b);
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitX()), in_b(Vec3d::UnitY()), a, b);
    }
  }
}

/// Whether link A is link L or one of its ancestors.
template <class S>
constexpr bool on_path(int A, int L) {
  for (; L > 0; L = S::tree.link_parent[L])
    if (L == A) return true;
  return false;
}

/// Adds to G's row the row's coefficients (n on ω, f on the velocity of the
/// point p) times the motion subspace of every joint between the World and
/// link Link: the columns J's of a frame on that link.
template <class S, int Link, class T, class Motions, class Poses>
FLANGE_INLINE void add_frame_jacobian(const Motions& motions, const Poses& pose, const Vec3<T>& n, const Vec3<T>& f,
                                      const Vec3<T>& p, T* row) {
  for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    constexpr int L = decltype(l)::value;
    if constexpr (on_path<S>(L, Link)) {
      using LI = link_info<S, L>;
      const auto& m = std::get<L - 1>(motions);
      const link_pose<T>& P = pose[L];
      // With the point's lever arm folded into the torque: n·ω + f·(v + ω × (p − r)) = (n + (p − r) × f)·ω + f·v.
      const Vec3<T> nn = P.R * (n + (p - P.r).cross(f)), ff = P.R * f;
      [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
        ((row[LI::v + K] += [&] {
           const auto c = m.template col<K>();
           return nn.dot(c.ang.dense()) + ff.dot(c.lin.dense());
         }()),
         ...);
      }(std::make_integer_sequence<int, LI::nv>{});
    }
  });
}

/// The loops' constraints at (q, v): Φ(q), Φ̇ = G·v, G, Ġ·v, and each row's
/// coefficients.
template <class S, class T>
struct loop_terms {
  static constexpr int m = n_constraints<S>(), n = S::n_v;
  std::array<T, m> phi, phid, bias;
  Eigen::Matrix<T, m, n> G;
  std::array<constraint_row<T>, m> rows;
};

template <class S, class T, class Motions>
loop_terms<S, T> loop_kinematics_at(const S& scene, const Motions& motions, const T* v) {
  constexpr int m = n_constraints<S>();
  const auto ls = loop_link_states<S, T>(motions, v);
  loop_terms<S, T> r;
  r.G.setZero();
  for_cuts<S>([&](auto k) {
    using CI = cut_info<S, decltype(k)::value>;
    if constexpr (CI::rows > 0) {
      const auto a = motion_of_set<S, CI::set_a, T>(scene, ls);
      const auto b = motion_of_set<S, CI::set_b, T>(scene, ls);
      cut_constraint<S, decltype(k)::value>(scene, a, b, r.rows.data());
      for (int i = cut_row<S, decltype(k)::value>(); i < cut_row<S, decltype(k)::value>() + CI::rows; ++i) {
        const auto& w = r.rows[i];
        T* g = r.G.data() + i;  // column-major: row i, stride m
        std::array<T, S::n_v> row{};
        add_frame_jacobian<S, CI::link_a>(motions, ls.pose, w.wa, w.va, a.r, row.data());
        add_frame_jacobian<S, CI::link_b>(motions, ls.pose, w.wb, w.vb, b.r, row.data());
        for (int j = 0; j < S::n_v; ++j) g[j * m] = row[j];
      }
    }
  });
  for (int i = 0; i < m; ++i) {
    r.phi[i] = r.rows[i].phi;
    r.phid[i] = r.rows[i].phid;
    r.bias[i] = r.rows[i].bias;
  }
  return r;
}

/// The same from (q, v).
template <class S, class T>
loop_terms<S, T> loop_kinematics(const S& scene, const T* q, const T* v) {
  const auto motions = link_motions<spatial_algebra, T, true>(scene, q);
  return loop_kinematics_at<S>(scene, motions, v);
}

/// The scene's size: the largest distance of a frame from its link's origin.
template <class S>
double characteristic_length(const S& scene) {
  double L = 0;
  for (const auto& o : scene.model().set_offset) L = std::max(L, o.norm());
  return L > 0 ? L : 1.0;
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
    for (int i = j + 1; i < M; ++i)
      for (int k = j + 1; k < M; ++k) A(p[i], p[k]) -= L(p[i], j) * L(p[k], j) * dj;
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

/// v̇ for the constrained equations of motion, given the factors of M
/// (ldlt.hpp) and y = M⁻¹·(τ − b).
///
/// With M = W·Wᵀ (W = L·√D) and z = Wᵀ·v̇, the accelerations are the least
/// change ‖z − Wᵀ·y‖ with Bᵀ·z = γ = −Ġ·v, B = W⁻¹·Gᵀ. Modified Gram–Schmidt
/// with column pivoting gives B·P = Q·R, and z = Wᵀ·y + Q·w with
/// R₁₁ᵀ·(Qᵀ·Wᵀ·y + w) = (Pᵀ·γ): v̇ = y + W⁻ᵀ·Q·w. The triangular solve
/// divides by R_jj damped, R_jj / (R_jj² + μ²), refined by a few sweeps:
/// a direction in which the constraints are (nearly) redundant, at a
/// singular position, is not divided by its vanishing R_jj. Working on B
/// rather than on G·M⁻¹·Gᵀ = Bᵀ·B keeps the conditioning to cond(B).
///
/// With lambda given, also the constraint forces λ (row by row: Gᵀ·λ is
/// their generalized force), from R₁₁·(Pᵀ·λ) = Qᵀ·(z − Wᵀ·y).
template <class S, class T, class MM, class Motions>
void constrained_accelerations(const S& scene, const Motions& motions, const MM& Mf, const ldlt_pivots<S::n_v, T>& f,
                               const T* v, const T* y, T* vdot, T* lambda = nullptr) {
  using std::sqrt;
  constexpr int n = S::n_v, m = n_constraints<S>();
  const auto k = loop_kinematics_at<S>(scene, motions, v);
  std::array<T, n> s;
  for (int i = 0; i < n; ++i) s[i] = sqrt(f.inv_d[i]);
  std::array<std::array<T, n>, m> B;
  std::array<T, m> gamma, norm2;
  std::array<int, m> p;
  for (int c = 0; c < m; ++c) {
    std::array<T, n> g;
    for (int i = 0; i < n; ++i) g[i] = k.G(c, i);
    ldlt_forward_half<n>(Mf, s, g.data(), B[c].data());
    gamma[c] = -k.bias[c];
    p[c] = c;
    norm2[c] = T(0);
    for (int i = 0; i < n; ++i) norm2[c] += B[c][i] * B[c][i];
  }
  T largest(0);
  // Each column's damping yardstick: its own squared norm in B, raised by
  // how small its row of G is against the largest (rows in comparable units):
  // a row that vanishes at a singular position is damped, a row that is only
  // small in B because of the masses is not.
  std::array<T, m> own = norm2;
  {
    const auto units = row_units(scene);
    std::array<T, m> g2;
    T g2max(0);
    for (int c = 0; c < m; ++c) {
      g2[c] = T(0);
      for (int i = 0; i < n; ++i) g2[c] += k.G(c, i) * k.G(c, i);
      g2[c] *= T(units[c] * units[c]);
      if (g2[c] > g2max) g2max = g2[c];
    }
    for (int c = 0; c < m; ++c)
      if (g2[c] * T(1e30) > g2max) own[c] = own[c] * g2max / g2[c];
      else own[c] = T(1e300);  // a row of zeros: never divided by
  }
  for (int c = 0; c < m; ++c)
    if (norm2[c] > largest) largest = norm2[c];
  // Q's columns overwrite B's; R's row j is pivot step j, its columns are kept
  // by original index (later swaps of p must not move them).
  std::array<std::array<T, m>, m> R;
  int rank = 0;
  for (int j = 0; j < m; ++j) {
    int best = j;
    for (int c = j + 1; c < m; ++c)
      if (norm2[p[c]] > norm2[p[best]]) best = c;
    std::swap(p[j], p[best]);
    const int cj = p[j];
    T nn(0);
    for (int i = 0; i < n; ++i) nn += B[cj][i] * B[cj][i];
    if (!(nn > T(1e-30) * largest)) break;  // exactly dependent: nothing left to damp
    const T r = sqrt(nn);
    R[j][cj] = r;
    for (int i = 0; i < n; ++i) B[cj][i] /= r;
    for (int c = j + 1; c < m; ++c) {
      const int cc = p[c];
      T d(0);
      for (int i = 0; i < n; ++i) d += B[cj][i] * B[cc][i];
      R[j][cc] = d;
      for (int i = 0; i < n; ++i) B[cc][i] -= d * B[cj][i];
      norm2[cc] = T(0);
      for (int i = 0; i < n; ++i) norm2[cc] += B[cc][i] * B[cc][i];
    }
    rank = j + 1;
  }
  // z0 = Wᵀ·y = √D·Lᵀ·y, and u = Qᵀ·z0 + w from R₁₁ᵀ·u = (Pᵀ·γ)₁.
  std::array<T, n> z0;
  for (int i = 0; i < n; ++i) {
    T x = y[i];
    for (int kk = i + 1; kk < n; ++kk) x += Mf(kk, i) * y[kk];
    z0[i] = x / s[i];
  }
  std::array<T, m> u{}, res, du;
  for (int sweep = 0; sweep < constraint_sweeps; ++sweep) {
    for (int j = 0; j < rank; ++j) {  // res = (Pᵀ·γ)₁ − R₁₁ᵀ·u
      T x = gamma[p[j]];
      for (int i = 0; i <= j; ++i) x -= R[i][p[j]] * u[i];
      res[j] = x;
    }
    for (int j = 0; j < rank; ++j) {  // R₁₁ᵀ·du = res, each division damped
      T x = res[j];
      for (int i = 0; i < j; ++i) x -= R[i][p[j]] * du[i];
      const T rjj = R[j][p[j]];
      du[j] = x * rjj / (rjj * rjj + T(constraint_damping * constraint_damping) * own[p[j]]);
    }
    for (int j = 0; j < rank; ++j) u[j] += du[j];
  }
  std::array<T, n> dz;
  std::array<T, m> w;
  for (int i = 0; i < n; ++i) dz[i] = T(0);
  for (int j = 0; j < rank; ++j) {
    T qz(0);
    for (int i = 0; i < n; ++i) qz += B[p[j]][i] * z0[i];
    w[j] = u[j] - qz;
    for (int i = 0; i < n; ++i) dz[i] += w[j] * B[p[j]][i];
  }
  if (lambda) {
    for (int j = m - 1; j >= 0; --j) {
      if (j >= rank) {
        lambda[p[j]] = T(0);
        continue;
      }
      T x = w[j];
      for (int c = j + 1; c < rank; ++c) x -= R[j][p[c]] * lambda[p[c]];
      lambda[p[j]] = x / R[j][p[j]];
    }
  }
  std::array<T, n> dv;
  ldlt_backward_half<n>(Mf, s, dz.data(), dv.data());
  for (int i = 0; i < n; ++i) vdot[i] = y[i] + dv[i];
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

/// Moves (q, v) onto the loops' constraints, changing only the rates i with
/// free[i] (and their joints' coordinates): Newton steps on Φ(q) = 0, each
/// the least change Δv = G_fᵀ·(G_f·G_fᵀ)⁺·(−Φ) applied through the joints'
/// q̇ (and normalize), until |Φ| stops shrinking or is at round-off; then
/// v ← v + G_fᵀ·(G_f·G_fᵀ)⁺·(−G·v). Reports what is left; the caller judges it.
template <class S>
closure project_onto_loops(const S& scene, double* q, double* v, const std::array<bool, S::n_v>& free,
                           int max_iterations = 50) {
  constexpr int n = S::n_v, m = n_constraints<S>();
  closure r;
  if constexpr (m > 0) {
    const double tol = 8 * std::numeric_limits<double>::epsilon() * length_scale(scene);
    std::array<double, n> zero{};
    auto masked = [&](const loop_terms<S, double>& k) {
      Eigen::Matrix<double, m, n> G = k.G;
      for (int j = 0; j < n; ++j)
        if (!free[j]) G.col(j).setZero();
      return G;
    };
    // Δv = G_fᵀ·(G_f·G_fᵀ)⁺·rhs
    auto least_change = [&](const Eigen::Matrix<double, m, n>& G, const std::array<double, m>& rhs) {
      Eigen::Matrix<double, m, m> A = G * G.transpose();
      std::array<double, m> mu;
      solve_semidefinite<m>(A, rhs.data(), mu.data());
      Eigen::Matrix<double, n, 1> dv = G.transpose() * Eigen::Map<const Eigen::Matrix<double, m, 1>>(mu.data());
      return dv;
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
    auto k = loop_kinematics<S>(scene, q, zero.data());
    r.phi = worst(k.phi, &r.worst_row);
    // Newton with backtracking: a step that does not shrink |Φ| is halved
    // (far from the solution a full step can overshoot), up to 30 times.
    while (r.phi > tol && r.iterations < max_iterations) {
      std::array<double, m> rhs;
      for (int i = 0; i < m; ++i) rhs[i] = -k.phi[i];
      const auto dv = least_change(masked(k), rhs);
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
          j.normalize(q + LI::q);
        });
        const auto kk = loop_kinematics<S>(scene, q, zero.data());
        if (norm2(kk.phi) < norm2(k.phi)) {  // the merit is |Φ|₂: Newton's step is a descent direction for it
          shrank = true;
          k = kk;
          r.phi = worst(k.phi, &r.worst_row);
        }
      }
      ++r.iterations;
      if (!shrank) {  // a minimum of |Φ| that is not zero: the loop cannot close here
        std::copy(q0.begin(), q0.end(), q);
        break;
      }
    }
    std::array<double, m> gv;
    for (int i = 0; i < m; ++i) {
      gv[i] = 0;
      for (int j = 0; j < n; ++j) gv[i] -= k.G(i, j) * v[j];
    }
    const auto dv = least_change(masked(k), gv);
    for (int j = 0; j < n; ++j) v[j] += dv[j];
    for (int i = 0; i < m; ++i) {
      gv[i] = 0;
      for (int j = 0; j < n; ++j) gv[i] += k.G(i, j) * v[j];
    }
    r.phid = worst(gv);
  }
  return r;
}

}  // namespace flange::detail
