// ∂v̇/∂q, ∂v̇/∂v and ∂v̇/∂t of a tree of one-axis joints, exactly, from the
// derivatives of inverse dynamics (Carpentier and Mansard, "Analytical
// derivatives of rigid body dynamics algorithms", RSS 2018), in O(N²):
//
//   ID(q, v, v̇) = Q(t, q, v)  ⇒  ∂v̇/∂x = M⁻¹·(∂Q/∂x − ∂ID/∂x)  at v̇ = f(t, x)
//
// Everything is in world coordinates at the world origin (spatial vectors,
// angular part first), where moving joint j by q_j turns every quantity of
// its subtree by its column s_j: ∂X/∂q_j = s_j × X. With v_p, a_p the
// velocity and acceleration (−g included) of j's parent, u_j = s_j × v_p,
// ψ_j = s_j × a_p − u_j × v_p, and over the subtree of link i its composite
// inertia I_i, the sum B_i of the bodies' B_k·w = I_k·(v_k × w) − w ×* (I_k·v_k)
// − v_k ×* (I_k·w) and its wrench F_i:
//
//   j an ancestor of i, or i:  ∂τ_i/∂q_j = s_iᵀ·(B_i·u_j − I_i·ψ_j)
//                              ∂τ_i/∂v_j = −s_iᵀ·(B_i·s_j + 2·I_i·u_j)
//   i a strict ancestor of j:  ∂τ_i/∂q_j = s_iᵀ·(s_j ×* F_j + B_j·u_j − I_j·ψ_j)
//                              ∂τ_i/∂v_j = −s_iᵀ·(B_j·s_j + 2·I_j·u_j)
//
// and M's entries are s_iᵀ·I_i·s_j on the same pairs. A joint's own force Q
// (an axis law, a drive of time) is differentiated by dual numbers in its own
// q, v and t. One forward pass over the links, one backward pass that fills
// the pairs, and one Cholesky solve of M with 2N + 1 right-hand sides.
//
// Which scenes take it (analytic_derivatives<S>): a tree (no loop, nothing
// floating) of joints of one rate whose column is fixed in their link
// (Revolute, Prismatic, either way round, axes typed or given at run time),
// no force elements, and no joint force reading other joints' states (a drive
// τ(t, x)). simulate/jacobian.hpp takes dual numbers for every other scene.
#pragma once
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "flange/dynamics/algorithm.hpp"
#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/links.hpp"
#include "flange/math/dual.hpp"

namespace flange::detail {

using vec6 = Eigen::Matrix<double, 6, 1>;

/// a × b, always inlined (Eigen's cross of two blocks is a call under GCC).
FLANGE_INLINE Vec3d cross3(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// The motion cross product v × w (angular parts first).
FLANGE_INLINE vec6 motion_cross(const vec6& v, const vec6& w) {
  vec6 r;
  const Vec3d va = v.head<3>(), vl = v.tail<3>(), wa = w.head<3>(), wl = w.tail<3>();
  r << cross3(va, wa), cross3(va, wl) + cross3(vl, wa);
  return r;
}
/// The force cross product v ×* f.
FLANGE_INLINE vec6 force_cross(const vec6& v, const vec6& f) {
  vec6 r;
  const Vec3d va = v.head<3>(), vl = v.tail<3>(), fa = f.head<3>(), fl = f.tail<3>();
  r << cross3(va, fa) + cross3(vl, fl), cross3(va, fl);
  return r;
}
FLANGE_INLINE Mat3d skew(const Vec3d& a) {
  Mat3d r;
  r << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return r;
}

/// A rigid body's spatial inertia at the world origin: mass, first moment
/// h = m·c and rotational inertia about the origin, world coordinates.
struct world_inertia {
  double m;
  Vec3d h;
  Mat3d I;
  /// I·x: the momentum of motion x.
  FLANGE_INLINE vec6 operator*(const vec6& x) const {
    vec6 r;
    const Vec3d xa = x.head<3>(), xl = x.tail<3>();
    r << I * xa + cross3(h, xl), m * xl - cross3(h, xa);
    return r;
  }
};

/// A link's inertia (m, h, I in link coordinates about the link origin) at the
/// link's world pose (R: link → world, r: its origin).
FLANGE_INLINE world_inertia to_world(const rigid_inertia<double>& b, const Mat3d& R, const Vec3d& r) {
  const Vec3d Rh = R * b.h;
  Mat3d I = R * b.I * R.transpose() - b.m * r * r.transpose() - Rh * r.transpose() - r * Rh.transpose();
  I.diagonal().array() += b.m * r.squaredNorm() + 2 * r.dot(Rh);
  return {b.m, Rh + b.m * r, I};
}

/// The sum of B_k over bodies k, where B_k·w = I_k·(v_k × w) − w ×* (I_k·v_k)
/// − v_k ×* (I_k·w). Written out by 3 × 3 blocks (W = ω̃, V = ṽ, H = h̃ for
/// I_k = [I H; −H m]), B_k = X + Xᵀ + [ℓ̃ p̃; p̃ 0] with X = I_k·(v_k×) and
/// (ℓ, p) = I_k·v_k, its right half is zero and its left half is
/// T = I·W + H·V + (I·W + H·V)ᵀ + ℓ̃ above K = 2·p̃: B·w reads w's angular part
/// alone.
struct velocity_coupling {
  Mat3d T, K;
  velocity_coupling& operator+=(const velocity_coupling& o) {
    T += o.T;
    K += o.K;
    return *this;
  }
  /// B·w.
  FLANGE_INLINE vec6 operator*(const vec6& w) const {
    vec6 r;
    r << T * w.template head<3>(), K * w.template head<3>();
    return r;
  }
  /// The angular part of Bᵀ·s (its linear part is zero).
  FLANGE_INLINE Vec3d transposed_times(const vec6& s) const {
    return T.transpose() * s.template head<3>() + K.transpose() * s.template tail<3>();
  }
};
FLANGE_INLINE velocity_coupling coupling_of(const world_inertia& I, const vec6& v) {
  const Vec3d w = v.template head<3>(), vl = v.template tail<3>();
  const Mat3d X = I.I * skew(w) + skew(I.h) * skew(vl);
  const vec6 h = I * v;
  return {X + X.transpose() + skew(h.template head<3>()), 2 * skew(h.template tail<3>())};
}

/// The rotation matrix of a typed rotation E (x_child = E·x_parent).
template <class E>
Mat3d dense_rotation(const E& e) {
  Mat3d R;
  for (int k = 0; k < 3; ++k) R.col(k) = rot(e, to_svec(Vec3d(Vec3d::Unit(k)))).dense();
  return R;
}

/// Whether joint type J is one the analytic derivatives handle: one rate, its
/// column fixed in its link, its force (if any) its own.
template <class J>
constexpr bool one_axis_joint() {
  return J::nq == 1 && J::nv == 1 && fixed_subspace<J> && !force_reads_state<J>();
}

/// Whether the scene's ∂v̇/∂x comes from analytic_derivatives (above).
template <class S>
constexpr bool analytic_derivatives() {
  if constexpr (!walkable<S> || S::tree.n_cuts > 0 || S::tree.n_links < 2) {
    return false;
  } else {
    constexpr auto loads = load_flags<S>::value;
    for (int L = 0; L < S::tree.n_links; ++L)
      if (loads.torque[L] || loads.force[L]) return false;
    return []<int... L>(std::integer_sequence<int, L...>) {
      return (one_axis_joint<typename link_info<S, L + 1>::joint_type>() && ...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  }
}

/// The matrix acceleration_derivatives fills: a row per rate, in link order.
template <class S>
using derivative_rows = Eigen::Matrix<double, S::n_v, 2 * S::n_v + 1, Eigen::RowMajor>;

/// Whether jacobian() takes the analytic derivatives: where they apply and
/// the scene has two rates or more. With one rate, dual numbers through the
/// derivative cost less (benchmarks/jacobian: a one-link chain 136 ns by
/// dual numbers, 232 ns analytic; two links 1,694 against 538 ns).
template <class S>
constexpr bool analytic_jacobian() {
  return analytic_derivatives<S>() && S::n_v >= 2;
}

/// ∂v̇/∂q, ∂v̇/∂v and ∂v̇/∂t at (t, q, v), given v̇ there, as the columns of
/// out (columns in rate order; row r is rate derivative_row_rate<S>[r]).
template <class S>
void acceleration_derivatives(const S& scene, double t, const double* q, const double* v, const double* vdot,
                              derivative_rows<S>& out) {
  static_assert(analytic_derivatives<S>() && S::n_q == S::n_v);
  constexpr int NL = S::tree.n_links, N = S::n_v;
  constexpr auto parent = [] {
    std::array<int, NL> p{};
    for (int L = 0; L < NL; ++L) p[L] = S::tree.link_parent[L];
    return p;
  }();
  constexpr auto rate = [] {
    std::array<int, NL> r{};
    for (int L = 1; L < NL; ++L) r[L] = S::tree.v_offset[S::tree.link_joint[L]];
    return r;
  }();

  // Each link's motion at q, densified: E (parent → link), p (its origin in
  // the parent's coordinates) and its column (link coordinates).
  std::array<Mat3d, NL> E;
  std::array<Vec3d, NL> p;
  std::array<vec6, NL> col;
  {
    const auto motions = link_motions<spatial_algebra, double, true>(scene, q);
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value;
      const auto& m = std::get<L - 1>(motions);
      E[L] = dense_rotation(m.E());
      p[L] = m.p.dense();
      const auto c = m.template col<0>();
      col[L] << c.ang.dense(), c.lin.dense();
    });
  }

  // Down the tree: poses, the columns, velocities and accelerations in the
  // world, each body's inertia, wrench and velocity coupling.
  std::array<Mat3d, NL> R;
  std::array<Vec3d, NL> r;
  std::array<vec6, NL> s, vel, acc, u, psi, F;
  std::array<world_inertia, NL> Ic;
  std::array<velocity_coupling, NL> Bc;
  R[0].setIdentity();
  r[0].setZero();
  vel[0].setZero();
  acc[0].setZero();
  if constexpr (S::has_gravity) acc[0].template tail<3>() = scene.model().minus_g;
  for (int L = 1; L < NL; ++L) {
    const int P = parent[L];
    R[L] = R[P] * E[L].transpose();
    r[L] = r[P] + R[P] * p[L];
    const Vec3d w = R[L] * col[L].template head<3>();
    s[L] << w, R[L] * col[L].template tail<3>() + cross3(r[L], w);
    const double qd = v[rate[L]], qdd = vdot[rate[L]];
    vel[L] = vel[P] + s[L] * qd;
    acc[L] = acc[P] + s[L] * qdd + motion_cross(vel[L], s[L]) * qd;
    u[L] = motion_cross(s[L], vel[P]);
    psi[L] = motion_cross(s[L], acc[P]) - motion_cross(u[L], vel[P]);
    Ic[L] = to_world(scene.model().link[L], R[L], r[L]);
    F[L] = Ic[L] * acc[L] + force_cross(vel[L], Ic[L] * vel[L]);
    Bc[L] = coupling_of(Ic[L], vel[L]);
  }

  // Up the tree: the composites, then the pairs of link L with its ancestors
  // (M and the derivatives are zero between links on different branches).
  // Rows in link order (parents first), so that M's factor keeps the tree's
  // zeros; columns in rate order.
  Eigen::Matrix<double, N, N> M;
  constexpr bool chain = [] {
    for (int L = 1; L < NL; ++L)
      if (S::tree.link_parent[L] != L - 1) return false;
    return true;
  }();
  if constexpr (!chain) out.setZero();
  for (int L = NL - 1; L >= 1; --L) {
    const int i = rate[L];
    const vec6 y = Ic[L] * s[L];
    const Vec3d z = Bc[L].transposed_times(s[L]);
    for (int j = L; j != 0; j = parent[j]) {
      const int k = rate[j];
      M(L - 1, j - 1) = y.dot(s[j]);
      out(L - 1, k) = y.dot(psi[j]) - z.dot(u[j].template head<3>());
      out(L - 1, N + k) = z.dot(s[j].template head<3>()) + 2 * y.dot(u[j]);
    }
    const vec6 G = force_cross(s[L], F[L]) + Bc[L] * u[L] - Ic[L] * psi[L];
    const vec6 H = Bc[L] * s[L] + 2 * (Ic[L] * u[L]);
    for (int j = parent[L]; j != 0; j = parent[j]) {
      out(j - 1, i) = -s[j].dot(G);
      out(j - 1, N + i) = s[j].dot(H);
    }
    if (const int P = parent[L]; P != 0) {
      Ic[P].m += Ic[L].m;
      Ic[P].h += Ic[L].h;
      Ic[P].I += Ic[L].I;
      Bc[P] += Bc[L];
      F[P] += F[L];
    }
  }
  out.col(2 * N).setZero();
  // The joints' own forces, each in its own q, v and the time.
  if constexpr (has_joint_forces<S>()) {
    using D = dual<double, 3>;
    std::array<D, S::n_q> qx;
    std::array<D, N> vx;
    for (int k = 0; k < S::n_q; ++k) qx[k] = D(q[k]);
    for (int k = 0; k < N; ++k) vx[k] = D(v[k]);
    const auto x = state_view(scene, qx.data(), vx.data());
    const D td = D::variable(t, 2);
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      if constexpr (has_generalized_force<typename LI::joint_type>) {
        qx[LI::q] = D::variable(q[LI::q], 0);
        vx[LI::v] = D::variable(v[LI::v], 1);
        D tau;
        scene.template component<LI::joint>().generalized_force(td, x, qx.data() + LI::q, vx.data() + LI::v, &tau);
        out(L - 1, LI::v) += tau.d[0];
        out(L - 1, N + LI::v) += tau.d[1];
        out(L - 1, 2 * N) += tau.d[2];
        qx[LI::q] = D(q[LI::q]);
        vx[LI::v] = D(v[LI::v]);
      }
    });
  }
  // M = Cᵀ·C (Featherstone's LTL factorization, leaves first: C has the
  // tree's zeros, where a root-first factor would join siblings), then
  // Cᵀ·C·X = out row by row, each step a row operation over 2N + 1 columns.
  for (int k = NL - 1; k >= 1; --k) {
    const double d = std::sqrt(M(k - 1, k - 1));
    M(k - 1, k - 1) = d;
    for (int i = parent[k]; i != 0; i = parent[i]) M(k - 1, i - 1) /= d;
    for (int i = parent[k]; i != 0; i = parent[i])
      for (int j = i; j != 0; j = parent[j]) M(i - 1, j - 1) -= M(k - 1, i - 1) * M(k - 1, j - 1);
  }
  // In blocks of columns small enough to stay in the first-level cache.
  auto solve = [&]<int W>(int c0, std::integral_constant<int, W>) {
    auto row = [&](int k) { return out.row(k - 1).template segment<W>(c0); };
    for (int k = NL - 1; k >= 1; --k) {
      row(k) /= M(k - 1, k - 1);
      for (int i = parent[k]; i != 0; i = parent[i]) row(i) -= M(k - 1, i - 1) * row(k);
    }
    for (int k = 1; k < NL; ++k) {
      for (int i = parent[k]; i != 0; i = parent[i]) row(k) -= M(k - 1, i - 1) * row(i);
      row(k) /= M(k - 1, k - 1);
    }
  };
  constexpr int C = 2 * N + 1, W = C < 32 ? C : 32;
  int c0 = 0;
  for (; c0 + W <= C; c0 += W) solve(c0, std::integral_constant<int, W>{});
  if constexpr (C % W != 0) solve(C - C % W, std::integral_constant<int, C % W>{});
}

/// The rate of row r of acceleration_derivatives' result (links in order).
template <class S>
inline constexpr auto derivative_row_rate = [] {
  std::array<int, S::n_v> r{};
  for (int L = 1; L < S::tree.n_links; ++L) r[L - 1] = S::tree.v_offset[S::tree.link_joint[L]];
  return r;
}();

}  // namespace flange::detail
