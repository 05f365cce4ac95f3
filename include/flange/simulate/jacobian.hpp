// The exact Jacobian ∂f/∂x of a scene's derivative (used by rosenbrock4.hpp
// and linearize.hpp): for a tree of one-axis joints, balls (a Spherical,
// a floating base's FreeMotion) and joints of rates in series (a Universal,
// a Cylindrical, a Planar), from the analytic derivatives of inverse
// dynamics (dynamics/derivatives.hpp); for a scene with loops whose loop
// solve is exact at x, by implicit differentiation of its constrained system
// (jacobian_loops, below: the same passes on its tree where they take it,
// the loops' rows differentiated through the tree's motions,
// dynamics/loop_derivatives.hpp); for every other scene by forward-mode dual
// numbers through the scalar-templated dynamics (jacobian_dual, which is
// also there for any scene).
//
// jacobian_finite_difference is the usual stand-in, central differences, for
// comparison: 2·n derivative evaluations and about 1e-10 relative error,
// against one dual-number evaluation carrying n directions (or a few, of at
// most 16 directions each, for a large scene).
//
// Each function has two forms: (scene, t, x, J) for ∂f/∂x alone, and
// (scene, t, x, J, dfdt) that also writes ∂f/∂t into *dfdt, as rosenbrock4
// needs. The time is then one direction more of the dual numbers (the paper's
// arm, two states: three directions instead of two), so ask for it only where
// it is used; given a null dfdt the second form computes it and drops it.
//
// Inputs take part when they are generic in their scalar (a lambda of
// (auto t) or (auto t, const auto& x)); an input written for double is
// evaluated at the time's value and counts as constant in x.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "flange/dynamics/derivatives.hpp"
#include "flange/dynamics/loop_derivatives.hpp"
#include "flange/math/place_transposed.hpp"
#include "flange/math/quaternion.hpp"
#include "flange/math/dual.hpp"
#include "flange/simulate/system.hpp"

namespace flange {

namespace detail {
/// Whether a scene's n_state × n_state Jacobian fits Eigen's fixed-size
/// matrices, which live on the stack up to EIGEN_STACK_ALLOCATION_LIMIT
/// (128 KB unless the build sets it, 0 for no limit): 128 states.
template <class S>
constexpr bool jacobian_on_stack() {
  return EIGEN_STACK_ALLOCATION_LIMIT == 0 ||
         std::size_t(S::n_state) * std::size_t(S::n_state) * sizeof(double) <= std::size_t(EIGEN_STACK_ALLOCATION_LIMIT);
}
}  // namespace detail

/// ∂f/∂x's matrix: of fixed size on the stack, or for a scene of more
/// states than Eigen keeps there (a 64-joint floating-base tree: 141) sized
/// n_state × n_state at run time on the heap. jacobian(scene, t, x, J)
/// writes into one made before (make_jacobian_matrix), allocating nothing.
template <class S>
using jacobian_matrix = std::conditional_t<detail::jacobian_on_stack<S>(), Eigen::Matrix<double, S::n_state, S::n_state>,
                                           Eigen::MatrixXd>;

/// An n_state × n_state jacobian_matrix<S>, its entries not set.
template <class S>
jacobian_matrix<S> make_jacobian_matrix() {
  if constexpr (detail::jacobian_on_stack<S>()) return {};
  else return jacobian_matrix<S>(S::n_state, S::n_state);
}

namespace detail {
/// The matrix into(J) writes, made here: what the by-value forms return.
template <class S, class Into>
FLANGE_INLINE jacobian_matrix<S> made_by(Into&& into) {
  auto J = make_jacobian_matrix<S>();
  into(J);
  return J;
}
}  // namespace detail

/// The most directions one dual-number evaluation carries. A scene with more
/// (n_state of them, n_state + 1 with the time) is differentiated in passes
/// of equal width, each recomputing the values: a 34-state scene in 3 passes of 12 directions,
/// 39 value-and-derivative lanes against 36 in one pass, while the
/// derivative over dual<double, 12> compiles in 98 s against 122 s over
/// dual<double, 35> (its code is about as large: GCC unrolls the narrower
/// lanes fully; docs/performance.md, "Compile time").
inline constexpr int jacobian_max_directions = 16;

namespace detail {
/// Passes and directions per pass for n directions.
constexpr int jacobian_passes(int n) { return (n + jacobian_max_directions - 1) / jacobian_max_directions; }
constexpr int jacobian_width(int n) { return (n + jacobian_passes(n) - 1) / jacobian_passes(n); }

/// The dual numbers of the passes below: n states, and the time WithTime.
template <int n, bool WithTime>
using jacobian_dual_t = dual<double, jacobian_width(n + WithTime)>;

/// The passes of dual numbers that differentiate in the n states and, if
/// WithTime, the time (directions 0 … n − 1 the state, n the time),
/// jacobian_width of them a pass: body(xd, td, first) for each, where
/// direction first + l is lane l of xd and td and the others are constants.
/// Its results' lane l goes to column first + l, or to ∂/∂t when that is n
/// (lane_columns). Both, and the lambdas jacobian_dual gives them, are
/// always inlined: a tiny scene's Jacobian is a few of its derivatives, and
/// through the calls the paper's arm took 200 ns against 90.
template <int n, bool WithTime, class State, class Body>
FLANGE_INLINE void dual_passes(const State& x, double t, Body&& body) {
  using D = jacobian_dual_t<n, WithTime>;
  constexpr int W = jacobian_width(n + WithTime);
  std::array<D, n> xd;
  for (int first = 0; first < n + WithTime; first += W) {
    auto seed = [&](double value, int direction) FLANGE_INLINE_LAMBDA {
      return direction >= first && direction < first + W ? D::variable(value, direction - first) : D(value);
    };
    for (int i = 0; i < n; ++i) xd[i] = seed(x[i], i);
    body(std::as_const(xd), seed(t, n), first);
  }
}
/// For each lane l of the pass from `first` that is a direction, f(l, c)
/// with c its column (n: the time).
template <int n, bool WithTime, class F>
FLANGE_INLINE void lane_columns(int first, F&& f) {
  constexpr int W = jacobian_width(n + WithTime);
  for (int l = 0; l < W && first + l < n + WithTime; ++l) f(l, first + l);
}

/// jacobian_dual's work: ∂f/∂x into J and, if WithTime, ∂f/∂t into *dfdt
/// when it is given.
template <bool WithTime, class S, class State>
void jacobian_dual_into(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                        Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  S::require_state_size(x);
  constexpr int n = S::n_state;
  std::array<jacobian_dual_t<n, WithTime>, n> fd;
  dual_passes<n, WithTime>(x, t, [&](const auto& xd, const auto& td, int first) FLANGE_INLINE_LAMBDA {
    scene(xd, fd, td);
    lane_columns<n, WithTime>(first, [&](int l, int c) FLANGE_INLINE_LAMBDA {
      for (int i = 0; i < n; ++i)
        if (c < n) J(i, c) = fd[i].d[l];
        else if (dfdt) (*dfdt)(i) = fd[i].d[l];
    });
  });
}
}  // namespace detail

/// ∂f/∂x at (t, x) into J, by dual numbers.
template <class S, class State>
void jacobian_dual(const S& scene, double t, const State& x, jacobian_matrix<S>& J) {
  detail::jacobian_dual_into<false>(scene, t, x, J, nullptr);
}

/// ∂f/∂x at (t, x) into J, and ∂f/∂t into *dfdt (when not null), by dual
/// numbers.
template <class S, class State>
void jacobian_dual(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                   Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  detail::jacobian_dual_into<true>(scene, t, x, J, dfdt);
}

/// ∂f/∂x at (t, x) by dual numbers.
template <class S, class State>
jacobian_matrix<S> jacobian_dual(const S& scene, double t, const State& x) {
  return detail::made_by<S>([&](jacobian_matrix<S>& J) { jacobian_dual(scene, t, x, J); });
}

/// ∂f/∂x at (t, x), and ∂f/∂t into *dfdt (when not null), by dual numbers.
template <class S, class State>
jacobian_matrix<S> jacobian_dual(const S& scene, double t, const State& x, Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  return detail::made_by<S>([&](jacobian_matrix<S>& J) { jacobian_dual(scene, t, x, J, dfdt); });
}

namespace detail {
/// x's numbers in one array: x's own where it keeps them in one (data(), as
/// the derivative reads them: a std::array, a std::vector, an Eigen vector),
/// else copied into `copy`. Not copied where they need not be: the copy's
/// stores, read at once by the passes, held the crane's Jacobian up by 40
/// ns for 36 more instructions (108 against 70 ns; docs/performance.md).
template <class S, class State>
FLANGE_INLINE const double* state_numbers(const State& x, std::array<double, S::n_state>& copy) {
  if constexpr (requires { { x.data() } -> std::convertible_to<const double*>; }) {
    return x.data();
  } else {
    for (int i = 0; i < S::n_state; ++i) copy[i] = x[i];
    return copy.data();
  }
}

/// The column of J that column c of acceleration_derivatives' rows goes to:
/// rate c's coordinate (none, −1, for a ball's turns, which the quaternion's
/// columns take) for c < n_v, rate c − n_v's column after.
template <class S>
inline constexpr std::array<int, 2 * S::n_v> derivative_column_place = [] {
  std::array<int, 2 * S::n_v> c{};
  for (int k = 0; k < S::n_v; ++k) c[k] = rate_coordinate<S>[k], c[S::n_v + k] = S::n_q + k;
  return c;
}();

/// Whether jacobian() takes the analytic derivatives: wherever they apply,
/// but where the passes' fixed cost (and the loads' dual numbers) exceed
/// dual numbers through the derivative: a scene of one rate in the plane
/// (one revolute about a typed axis: 25 against 18 ns) or with force
/// elements on its link (the paper's arm, 60 against 27 ns), or of one link
/// with force elements (a ball on the ground, 1.9 against 1.7 µs). A scene
/// of one rate in space takes them (the one-link chain of a run-time axis,
/// its column's shape known to the passes: 46 against 92 ns), and so does
/// a free body without loads (six rates), 0.33 against 1.20 µs (probes and
/// build/benchmarks/jacobian's analytic_ns and dual_ns; docs/performance.md,
/// "The Jacobian").
template <class S>
constexpr bool jacobian_takes_analytic() {
  if constexpr (!analytic_derivatives<S>()) {
    return false;
  } else if constexpr (S::n_v == 1) {
    return !has_link_loads<S>() && planar_axis<S>() < 0;
  } else {
    return S::tree.n_links > 2 || !has_link_loads<S>();
  }
}

/// ∂f/∂x at (t, x) into J, and ∂f/∂t into *dfdt when given, from the
/// analytic derivatives (dynamics/derivatives.hpp), for a scene they apply to.
template <class S, class State>
void jacobian_analytic(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                       Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  static_assert(analytic_derivatives<S>());
  S::require_state_size(x);
  constexpr int nq = S::n_q, nv = S::n_v;
  std::array<double, S::n_state> copy;
  const double* const xs = state_numbers<S>(x, copy);
  // On a 32-byte boundary, so that the solve's four-number reads of its rows
  // never straddle two cache lines (math/tree_solve.hpp).
  alignas(32) detail::derivative_rows<S> d;
  if (const auto p = detail::acceleration_derivatives(scene, t, xs, xs + nq, d); p.index >= 0) {
    // M is singular here: the derivative says why (a state that is not
    // finite, or the joint whose pivot failed), in the scene's own words.
    typename S::state_type xa, f;
    std::copy_n(xs, S::n_state, xa.begin());
    scene(xa, f, t);
    detail::singular_mass_matrix<S>(p, t, xs, xs + nq);
  }
  // J's entries by their place in its (column-major) numbers, n_state a
  // column whether its size is fixed or set at run time.
  double* const Jn = J.data();
  auto at = [Jn](int r, int c) FLANGE_INLINE_LAMBDA -> double& { return Jn[r + std::size_t(c) * S::n_state]; };
  // q̇'s rows: zero but for the entries below; in a matrix sized at run
  // time a column's nq numbers at a time (Eigen's block of it goes a
  // number pair at a time: 40k instructions on a 141-state tree).
  if constexpr (detail::jacobian_on_stack<S>())
    J.template topRows<nq>().setZero();
  else
    for (int c = 0; c < S::n_state; ++c) std::fill_n(&at(0, c), nq, 0.0);
  // v̇'s rows: ∂/∂v, and ∂/∂q where a coordinate is its rate's (a joint of
  // one rate, rates in series, a ball's translations): d's rows turned into
  // J's columns (math/place_transposed.hpp).
  constexpr auto row = detail::derivative_row_rate<S>;
  constexpr auto coordinate = detail::rate_coordinate<S>;
  detail::place_transposed<detail::derivative_rows<S>::ColsAtCompileTime, S::n_state, row,
                           detail::derivative_column_place<S>>(d.data(), Jn, nq);
  for (int c = 0; c < nv; ++c)
    if (coordinate[c] >= 0) at(coordinate[c], nq + c) = 1;
  // A ball's quaternion Q = (x, y, z, w): q̇ = ½·Q ⊗ (ω, 0) (linear in Q and
  // in ω), and ∂v̇/∂Q through the turn δ (link coordinates) that a change of
  // Q makes, δ = 2·vec(Q* ⊗ dQ)/|Q|² (R is homogeneous in Q: a change along
  // Q turns nothing).
  detail::for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = detail::link_info<S, L>;
    if constexpr (detail::ball_links<S>[L]) {
      constexpr int qa = LI::joint_type::quaternion_at, qQ = LI::q + qa, vw = LI::v + qa;
      const double* Q = xs + qQ;
      const double* w = xs + nq + vw;
      const double x = Q[0], y = Q[1], z = Q[2], s = Q[3];
      // quaternion::rate's q̇ = ½·Q ⊗ (ω, 0), written out: ∂q̇/∂Q (its
      // columns x, y, z, s) and ∂q̇/∂ω, each entry one number (the rate
      // taken along a unit vector multiplies by its zeros).
      const double hw[3] = {0.5 * w[0], 0.5 * w[1], 0.5 * w[2]};
      const double dQ[4][4] = {{0, hw[2], -hw[1], hw[0]},
                               {-hw[2], 0, hw[0], hw[1]},
                               {hw[1], -hw[0], 0, hw[2]},
                               {-hw[0], -hw[1], -hw[2], 0}};
      const double hx = 0.5 * x, hy = 0.5 * y, hz = 0.5 * z, hs = 0.5 * s;
      const double dw[4][3] = {{hs, -hz, hy}, {hz, hs, -hx}, {-hy, hx, hs}, {-hx, -hy, -hz}};
      for (int m = 0; m < 4; ++m)
        for (int k = 0; k < 4; ++k) at(qQ + k, qQ + m) = dQ[k][m];
      for (int m = 0; m < 3; ++m)
        for (int k = 0; k < 4; ++k) at(qQ + k, nq + vw + m) = dw[k][m];
      const double k2 = 2 / (x * x + y * y + z * z + s * s);
      // ∂δ/∂Q, column m: ∂v̇/∂Q_m = ∂v̇/∂δ · T(:, m), written down J's
      // column a row of d at a time.
      const double T[3][4] = {{k2 * s, k2 * z, -k2 * y, -k2 * x},
                              {-k2 * z, k2 * s, k2 * x, -k2 * y},
                              {k2 * y, -k2 * x, k2 * s, -k2 * z}};
      for (int m = 0; m < 4; ++m)
        for (int r = 0; r < nv; ++r)
          at(nq + row[r], qQ + m) = d(r, vw) * T[0][m] + d(r, vw + 1) * T[1][m] + d(r, vw + 2) * T[2][m];
    }
  });
  if (dfdt) {
    dfdt->template head<nq>().setZero();
    for (int r = 0; r < nv; ++r) (*dfdt)(nq + row[r]) = d(r, 2 * nv);
  }
}

/// The same, returned.
template <class S, class State>
jacobian_matrix<S> jacobian_analytic(const S& scene, double t, const State& x,
                                     Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  return made_by<S>([&](jacobian_matrix<S>& J) { jacobian_analytic(scene, t, x, J, dfdt); });
}

/// The blocks of [M −Gᵀ; G 0] that the implicit differentiation below
/// solves with: M = L·D·Lᵀ as the loop solve factored it; G's rows; from
/// them B = L⁻¹·Gᵀ, the Schur complement S = G·M⁻¹·Gᵀ = Bᵀ·D⁻¹·B, factored
/// the same way, and Z = M⁻¹·Gᵀ. The loop solve kept every row undamped,
/// so S is as well conditioned as its rows (each at least 100 times the
/// damping away from depending on the rows before it).
template <class S>
struct loop_blocks {
  static constexpr int nv = S::n_v, m = n_constraints<S>();
  const factored_mass<S, double>& mass;
  std::array<std::array<double, nv>, m> G, Z;  // row c of G; column c of M⁻¹·Gᵀ
  Eigen::Matrix<double, m, m> Sc;
  ldlt_pivots<m, double> fS;

  explicit loop_blocks(const factored_mass<S, double>& factored) : mass(factored) {}
  /// From G's entries g(c, i); false where S fails its pivot test (which
  /// an exact loop solve rules out).
  template <class Entry>
  bool factor(Entry&& g) {
    std::array<double, m> yard;
    for (int c = 0; c < m; ++c) {
      for (int i = 0; i < nv; ++i) G[c][i] = g(c, i);
      ldlt_forward<nv>(mass.M, G[c].data(), Z[c].data(), mass_factor<S>{});  // B's column c, for now
    }
    for (int c = 0; c < m; ++c)
      for (int e = 0; e <= c; ++e) {
        double x = 0;
        for (int i = 0; i < nv; ++i) x += Z[c][i] * Z[e][i] * mass.f.inv_d[i];
        Sc(c, e) = Sc(e, c) = x;
      }
    for (int c = 0; c < m; ++c) yard[c] = Sc(c, c);
    if (ldlt_factor<m>(Sc, fS, yard.data()).index >= 0) return false;
    for (int c = 0; c < m; ++c) {
      for (int i = 0; i < nv; ++i) Z[c][i] *= mass.f.inv_d[i];
      ldlt_backward<nv>(mass.M, Z[c].data(), Z[c].data(), mass_factor<S>{});
    }
    return true;
  }
  /// y = M⁻¹·y.
  void solve_mass(double* y) const {
    ldlt_forward<nv>(mass.M, y, y, mass_factor<S>{});
    for (int i = 0; i < nv; ++i) y[i] *= mass.f.inv_d[i];
    ldlt_backward<nv>(mass.M, y, y, mass_factor<S>{});
  }
  /// One column of [M −Gᵀ; G 0]·[x; μ] = [−∂F; −∂C] from x0 = M⁻¹·(−∂F)
  /// (in x, which it becomes) and ∂C: S·μ = −∂C − G·x0, x = x0 + Z·μ.
  void constrain(double* x, const double* dC) const {
    std::array<double, m> r, mu;
    for (int e = 0; e < m; ++e) {
      double y = -dC[e];
      for (int i = 0; i < nv; ++i) y -= G[e][i] * x[i];
      r[e] = y;
    }
    ldlt_solve<m>(Sc, fS, r.data(), mu.data());
    for (int i = 0; i < nv; ++i)
      for (int e = 0; e < m; ++e) x[i] += Z[e][i] * mu[e];
  }
};

/// Whether the implicit differentiation of a scene with loops takes the
/// analytic passes (dynamics/derivatives.hpp) for its tree: a tree they
/// take whose every coordinate is its rate's (q̇ = v: no ball).
template <class S>
constexpr bool loops_take_passes() {
  if constexpr (!analytic_tree<S>() || S::n_q != S::n_v) {
    return false;
  } else {
    for (int k = 0; k < S::n_v; ++k)
      if (rate_coordinate<S>[k] != k) return false;
    return true;
  }
}

/// jacobian_loops_into's route where the analytic passes take the loop's
/// tree (loops_take_passes): M⁻¹·∂F is the passes' M⁻¹·(∂Q − ∂ID) at the
/// constrained v̇ (the constraint forces Gᵀ·λ given to them as forces held
/// fixed) plus M⁻¹·∂(Gᵀ)·λ; ∂G and ∂C come from the tree's motions and their
/// derivatives in q (dynamics/loop_derivatives.hpp), the cut's rows in dual
/// numbers in the directions of q alone. Every row is the time derivative
/// of a function of q (Φ̇ = G·v, dynamics/loops.hpp) and every coordinate
/// is its rate's (q̇ = v), so G = ∂Φ/∂q: ∂(G·v̇)/∂v is zero, and Ġ·v is a
/// quadratic form in v whose matrix, Φ's second derivatives, is symmetric,
/// so that ∂(Ġ·v)/∂v = 2·Ġ with Ġ = Σ_k ∂G/∂q_k·v_k, from the same lanes.
template <bool WithTime, class S>
bool implicit_by_passes(const S& scene, double t, const double* q, const double* v, const double* a,
                        const double* lambda, loop_blocks<S>& K, jacobian_matrix<S>& J,
                        Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  constexpr int nq = S::n_q, nv = S::n_v, m = n_constraints<S>();
  constexpr auto row = derivative_row_rate<S>;
  using D = jacobian_dual_t<nq, false>;
  constexpr int W = jacobian_width(nq);
  std::array<std::array<double, nv>, m> Gdot{};  // Ġ
  alignas(32) derivative_rows<S> d;
  loop_motion_state<S> st;
  loop_motions(scene, q, v, a, st);
  loop_lanes<S, D> k;
  for (int first = 0; first < nq; first += W) {
    loop_rows_lanes(scene, st, first, k);
    if (first == 0) {
      if (!K.factor([&](int c, int i) { return k.G[c][i].v; })) return false;
      std::array<double, nv> constraint_forces;  // Gᵀ·λ
      for (int i = 0; i < nv; ++i) {
        double f = 0;
        for (int c = 0; c < m; ++c) f += K.G[c][i] * lambda[c];
        constraint_forces[i] = f;
      }
      if (acceleration_derivatives(scene, t, q, v, d, nullptr, constraint_forces.data()).index >= 0) return false;
    }
    const auto& C = k.C;  // G·v̇ + Ġ·v at the solution's v̇
    for (int l = 0; l < W && first + l < nq; ++l) {
      const int c = first + l;
      // x0 = M⁻¹·(−∂F) = M⁻¹·∂(Gᵀ)·λ + the passes' column.
      std::array<double, nv> dv;
      std::array<double, m> dC;
      for (int i = 0; i < nv; ++i) {
        double h = 0;
        for (int e = 0; e < m; ++e) {
          h += k.G[e][i].d[l] * lambda[e];
          Gdot[e][i] += k.G[e][i].d[l] * v[c];
        }
        dv[i] = h;
      }
      K.solve_mass(dv.data());
      for (int r = 0; r < nv; ++r) dv[row[r]] += d(r, c);
      for (int e = 0; e < m; ++e) dC[e] = C[e].d[l];
      K.constrain(dv.data(), dC.data());
      for (int i = 0; i < nq; ++i) J(i, c) = 0;
      for (int i = 0; i < nv; ++i) J(nq + i, c) = dv[i];
    }
  }
  // ∂/∂v: the passes' columns, ∂C = 2·Ġ; q̇ = v.
  for (int c = 0; c < nv; ++c) {
    std::array<double, nv> dv;
    std::array<double, m> dC;
    for (int r = 0; r < nv; ++r) dv[row[r]] = d(r, nv + c);
    for (int e = 0; e < m; ++e) dC[e] = 2 * Gdot[e][c];
    K.constrain(dv.data(), dC.data());
    for (int i = 0; i < nq; ++i) J(i, nq + c) = i == c ? 1.0 : 0.0;
    for (int i = 0; i < nv; ++i) J(nq + i, nq + c) = dv[i];
  }
  if constexpr (WithTime) {
    if (dfdt) {
      // ∂/∂t: the passes' column (C does not read the time).
      std::array<double, nv> dv;
      const std::array<double, m> dC{};
      for (int r = 0; r < nv; ++r) dv[row[r]] = d(r, 2 * nv);
      K.constrain(dv.data(), dC.data());
      dfdt->template head<nq>().setZero();
      for (int i = 0; i < nv; ++i) (*dfdt)(nq + i) = dv[i];
    }
  }
  return true;
}

/// jacobian_loops_into's route for every other loop scene: −∂F from inverse
/// dynamics, the joints' forces and Gᵀ·λ, ∂C from the loops' kinematics,
/// all in dual numbers in every direction of the state (and the time
/// WithTime).
template <bool WithTime, class S, class State>
bool implicit_by_dual_numbers(const S& scene, double t, const State& x, const double* a, const double* lambda,
                              loop_blocks<S>& K, jacobian_matrix<S>& J,
                              Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  using A = algebra_t<S>;
  constexpr int nq = S::n_q, nv = S::n_v, m = n_constraints<S>(), n = S::n_state;
  using D = jacobian_dual_t<n, WithTime>;
  std::array<D, nv> ad;
  for (int i = 0; i < nv; ++i) ad[i] = D(a[i]);
  bool factored = false;
  dual_passes<n, WithTime>(x, t, [&](const auto& xd, const D& td, int first) {
    if (first > 0 && !factored) return;
    const D* qd = xd.data();
    const D* vd = xd.data() + nq;
    const auto motions = algebra_motions<A>(scene, qd);
    decltype(auto) pose = pose_motions<A>(scene, qd, motions);
    const auto k = loop_kinematics_at<S>(scene, pose, vd);
    if (first == 0) {
      factored = K.factor([&](int c, int i) { return k.G(c, i).v; });
      if (!factored) return;
    }
    link_loads<S, D> n_ext, f_ext;
    const auto xv = state_view(scene, qd, vd);
    gather_external<A>(scene, td, xv, motions, pose, n_ext, f_ext);
    std::array<D, nv> F;
    inverse_dynamics<A>(scene, motions, vd, ad.data(), n_ext, f_ext, F.data());
    if constexpr (has_joint_forces<S>()) {
      std::array<D, nv> tau;
      joint_forces(scene, td, xv, tau.data());
      for (int i = 0; i < nv; ++i) F[i] -= tau[i];
    }
    std::array<D, m> C;  // G·v̇ + Ġ·v at the solution's v̇
    for (int c = 0; c < m; ++c) {
      C[c] = k.bias[c];
      for (int i = 0; i < nv; ++i) {
        F[i] -= k.G(c, i) * lambda[c];
        C[c] += k.G(c, i) * a[i];
      }
    }
    // q̇'s rows: the joints' rates, differentiated as they are written.
    std::array<D, nq> qdot;
    joint_rates(scene, qd, vd, qdot.data());
    lane_columns<n, WithTime>(first, [&](int l, int c) {
      std::array<double, nv> dv;
      std::array<double, m> dC;
      for (int i = 0; i < nv; ++i) dv[i] = -F[i].d[l];
      K.solve_mass(dv.data());
      for (int e = 0; e < m; ++e) dC[e] = C[e].d[l];
      K.constrain(dv.data(), dC.data());
      if (c < n) {
        for (int i = 0; i < nq; ++i) J(i, c) = qdot[i].d[l];
        for (int i = 0; i < nv; ++i) J(nq + i, c) = dv[i];
      } else if (dfdt) {
        for (int i = 0; i < nq; ++i) (*dfdt)(i) = qdot[i].d[l];
        for (int i = 0; i < nv; ++i) (*dfdt)(nq + i) = dv[i];
      }
    });
  });
  return factored;
}

/// ∂f/∂x at (t, x), and ∂f/∂t into *dfdt when given, for a scene with loops,
/// by implicit differentiation of its constrained accelerations: v̇ and the
/// constraint forces λ solve
///
///   F = M·v̇ + b − τ − Gᵀ·λ = 0,   C = G·v̇ + Ġ·v = 0,
///
/// so that [M −Gᵀ; G 0]·[∂v̇; ∂λ] = −[∂F; ∂C], where ∂F and ∂C are the
/// derivatives at the solution's v̇ and λ held fixed, then one double solve
/// for each column by the blocks of the matrix (loop_blocks). Where the
/// analytic passes take the tree (loops_take_passes), M⁻¹·∂F comes from
/// them and ∂C from the loops' kinematics in dual numbers in q's directions
/// (implicit_by_passes); else both from dual numbers in every direction
/// (implicit_by_dual_numbers; no mass matrix, factorization or loop solve
/// in them). Only where the loop solve was the exact one (every constraint
/// row kept, no division damped: dynamics/loop_solve.hpp), and where S and
/// the passes' M pass their pivot tests, which an exact loop solve rules
/// out; false otherwise, and nothing written (a redundant constraint or a
/// singular position, which jacobian() then differentiates by dual numbers,
/// the damping and the rows left out included). WithTime: ∂f/∂t too, into
/// *dfdt when it is given.
template <bool WithTime, class S, class State>
bool jacobian_loops_into(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                         Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  static_assert(has_loops<S>);
  S::require_state_size(x);
  constexpr int nq = S::n_q, nv = S::n_v, m = n_constraints<S>(), n = S::n_state;
  std::array<double, n> copy;
  const double* const xs = state_numbers<S>(x, copy);
  std::array<double, nv> a;
  std::array<double, m> lambda;
  bool exact = false;
  factored_mass<S, double> mass;
  accelerations_and_constraint_forces(scene, t, xs, xs + nq, a.data(), lambda.data(), &exact, &mass);
  if (!exact) return false;
  loop_blocks<S> K(mass);
  if constexpr (loops_take_passes<S>())
    return implicit_by_passes<WithTime>(scene, t, xs, xs + nq, a.data(), lambda.data(), K, J, dfdt);
  else
    return implicit_by_dual_numbers<WithTime>(scene, t, x, a.data(), lambda.data(), K, J, dfdt);
}

/// ∂f/∂x at (t, x) into J by the implicit differentiation above.
template <class S, class State>
bool jacobian_loops(const S& scene, double t, const State& x, jacobian_matrix<S>& J) {
  return jacobian_loops_into<false>(scene, t, x, J, nullptr);
}

/// The same, and ∂f/∂t into *dfdt (when not null).
template <class S, class State>
bool jacobian_loops(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                    Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  return jacobian_loops_into<true>(scene, t, x, J, dfdt);
}

/// jacobian's choice of path; WithTime: ∂f/∂t too, into *dfdt when given.
template <bool WithTime, class S, class State>
void jacobian_into(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                   Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  if constexpr (jacobian_takes_analytic<S>()) {
    jacobian_analytic(scene, t, x, J, dfdt);
  } else if constexpr (has_loops<S>) {
    if (!jacobian_loops_into<WithTime>(scene, t, x, J, dfdt)) jacobian_dual_into<WithTime>(scene, t, x, J, dfdt);
  } else {
    jacobian_dual_into<WithTime>(scene, t, x, J, dfdt);
  }
}
}  // namespace detail

/// ∂f/∂x at (t, x) into J: analytic where dynamics/derivatives.hpp covers the
/// scene (jacobian_takes_analytic); for a scene with loops by implicit
/// differentiation where the loop solve is exact (detail::jacobian_loops);
/// else by dual numbers.
template <class S, class State>
void jacobian(const S& scene, double t, const State& x, jacobian_matrix<S>& J) {
  detail::jacobian_into<false>(scene, t, x, J, nullptr);
}

/// The same, and ∂f/∂t into *dfdt (when not null).
template <class S, class State>
void jacobian(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
              Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  detail::jacobian_into<true>(scene, t, x, J, dfdt);
}

/// ∂f/∂x at (t, x), returned.
template <class S, class State>
jacobian_matrix<S> jacobian(const S& scene, double t, const State& x) {
  return detail::made_by<S>([&](jacobian_matrix<S>& J) { jacobian(scene, t, x, J); });
}

/// The same, and ∂f/∂t into *dfdt (when not null).
template <class S, class State>
jacobian_matrix<S> jacobian(const S& scene, double t, const State& x, Eigen::Matrix<double, S::n_state, 1>* dfdt) {
  return detail::made_by<S>([&](jacobian_matrix<S>& J) { jacobian(scene, t, x, J, dfdt); });
}

/// ∂f/∂x (and ∂f/∂t into *dfdt) by central differences, step
/// h = ε^(1/3)·max(1, |x_k|), which balances truncation (h²) against rounding
/// (ε/h): about 1e-10 relative error.
template <class S, class State>
void jacobian_finite_difference(const S& scene, double t, const State& x, jacobian_matrix<S>& J,
                                Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  S::require_state_size(x);
  constexpr int n = S::n_state;
  const double cbrt_eps = std::cbrt(std::numeric_limits<double>::epsilon());
  std::array<double, n> xp, xm, fp, fm;
  for (int k = 0; k <= n; ++k) {
    if (k == n && !dfdt) break;
    std::copy_n(x.begin(), n, xp.begin());
    std::copy_n(x.begin(), n, xm.begin());
    double tp = t, tm = t;
    const double h = cbrt_eps * std::max(1.0, std::abs(k < n ? double(x[k]) : t));
    if (k < n) {
      xp[k] += h;
      xm[k] -= h;
    } else {
      tp += h;
      tm -= h;
    }
    scene(xp, fp, tp);
    scene(xm, fm, tm);
    for (int i = 0; i < n; ++i) {
      const double v = (fp[i] - fm[i]) / (2 * h);
      if (k < n) J(i, k) = v;
      else (*dfdt)(i) = v;
    }
  }
}

/// The same, returned.
template <class S, class State>
jacobian_matrix<S> jacobian_finite_difference(const S& scene, double t, const State& x,
                                              Eigen::Matrix<double, S::n_state, 1>* dfdt = nullptr) {
  return detail::made_by<S>([&](jacobian_matrix<S>& J) { jacobian_finite_difference(scene, t, x, J, dfdt); });
}

}  // namespace flange
