// ∂v̇/∂q, ∂v̇/∂v and ∂v̇/∂t of a tree of one-axis joints, balls and joints of
// rates in series, exactly, from the
// derivatives of inverse dynamics (Carpentier and Mansard, "Analytical
// derivatives of rigid body dynamics algorithms", RSS 2018):
//
//   ID(q, v, v̇) = Q(t, q, v)  ⇒  ∂v̇/∂x = M⁻¹·(∂Q/∂x − ∂ID/∂x)  at v̇ = f(t, x)
//
// Everything is in one fixed frame, link 1's at q (spatial vectors, angular
// part first; the algebra holds in any fixed frame: about the World's origin
// a base far from it would carry its lever arm into every inertia, and in
// link 1's axes its columns and inertia need no turn), where moving joint j
// by q_j turns every quantity of
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
// and M's entries are s_iᵀ·I_i·s_j on the same pairs. The passes are written
// once over a geometry: 3-D space, or for a planar scene (dynamics/algebra.hpp's
// planar_axis) the plane normal to its axis K, where a motion is ω along K
// and an in-plane velocity, an inertia is m, an in-plane first moment and
// I_KK, and B is T_KK and an in-plane k: a tenth of the arithmetic, and what
// it drops changes no q̈. A joint's own force Q is differentiated by dual
// numbers: an axis law or a drive of time in its own q, v and t, a drive that
// reads the state (τ(t, x), a PD law) in every direction. v̇ itself comes
// from the same passes: τ⁰ at v̇ = 0, v̇ = M⁻¹·(Q − τ⁰), then the
// accelerations corrected. One forward pass over the links, one backward pass that fills
// the pairs of a link and its ancestors (O(N²) on a chain), and one solve of
// M with 2N + 1 right-hand sides: by M's LTDL factor (O(N³) on a chain),
// or on a chain of 24 nodes or more (12 in the plane) by its articulated-body
// factor (math/chain_solve.hpp, O(N²)). A pivot of either factor is tested
// against the inertia its node's composite has about the fixed point. The
// passes are compiled twice, for every x86-64 and for AVX2 without fused
// multiply-adds, and the processor's is chosen at run time: the same
// numbers to the bit (acceleration_derivatives, at the end).
//
// The force elements' loads (torques, springs, dampers, world forces,
// contacts) are computed by their own code in dual numbers, turned into
// wrenches W_L at that point; they enter τ_i as −s_iᵀ·Σ W over i's subtree,
// whose derivative adds s_iᵀ·∂W/∂x and, for q_j above i, the turn of s_i:
// −(s_j × s_i)ᵀ·Σ W. In space, where no element reads the joint state
// (local_loads), each element's dual numbers run in the motions of the links
// it sits on alone, 12 directions a link (a turn and a shift of its pose, a
// change of its twist) and the time, 13 for a contact with the ground
// whatever the scene's size; the columns carry them to the state's
// directions (q_j of an ancestor of link P moves P by s_j and changes its
// twist v_P by s_j × v_P − u_j; v_j changes the twist by s_j). Otherwise
// (a load that reads the state, a planar scene) they run in every direction
// of the state, through the whole tree's kinematics.
//
// The passes run over nodes, one per rate (derivative_nodes): a joint of one
// rate is a node, and so is each translation of a ball (core/joint.hpp,
// ball_rates: a Spherical, a FreeMotion), a prismatic column fixed in the
// parent. A ball's three rotation rates are ω in its link: all three columns
// are fixed in the link and turn with each of them, and each reads the
// velocity V before the ball. So they are three nodes in a row whose u and ψ
// take V's velocity and acceleration, whose pairs take the ancestor's formula
// both ways (row a, column b of one ball: s_aᵀ·(B·u_b − I·ψ_b)), and whose
// ∂/∂v reads u_b + ½·s_b × (v_L − v_V) for u_b (the next columns' u do not
// move with ω). Their directions in q are the link's turns δ about its own
// axes (Q moving by ½·Q ⊗ (δ, 0)); simulate/jacobian.hpp maps them to the
// quaternion's four coordinates (R is homogeneous in Q).
//
// Where link 1 turns on a ball that every link hangs from (a floating base,
// a free body), or on a tree of up to four nodes hangs from the World by a
// Revolute or a Prismatic (whose link's axes put its axis on one of theirs),
// its nodes' columns in its own axes are known by shape: a translation
// (0, l), a turn (c·e_k, 0) about coordinate axis k. Their products
// (column_dot and the ones beside it) leave out the zero half, and the
// passes take those nodes written out, each node and its shape a constant.
//
// A link's nodes but its last carry no body, and each one's only child is
// the next node of its link: they share its subtree, and so its composite
// inertia, coupling and wrench, which the passes keep at the last node
// alone (top) rather than copy down the link.
//
// A joint of several rates that moves as one-rate joints in series
// (core/joint.hpp, sequential_rates: a Universal, a Cylindrical, a Planar) is
// as many nodes in a row, each of them a one-axis joint's node: rate k's
// column is fixed in the frame the rates before it have moved (a massless
// link between them), and q_k's direction is that column.
//
// Which scenes take it (analytic_derivatives<S>): a tree (no loop) of joints
// of one rate whose column is fixed in their link (Revolute, Prismatic,
// either way round, axes typed or given at run time, any drive), of balls
// and of joints of rates in series, both connected frame_a toward the World,
// with any force elements. The tree of a scene with loops (analytic_tree<S>)
// takes them too, for simulate/jacobian.hpp's implicit differentiation of
// the constrained accelerations: given the loops' constraint forces Gᵀ·λ as
// generalized forces held fixed, their v̇ is the constrained one and their
// columns M⁻¹·(∂Q − ∂ID) at it. simulate/jacobian.hpp takes dual numbers for
// every other scene (a ball or a Universal or Cylindrical connected the other
// way round).
#pragma once
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "flange/detail/cpu.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/dynamics/external.hpp"
#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/links.hpp"
#include "flange/math/dual.hpp"
#include "flange/math/chain_solve.hpp"
#include "flange/math/quaternion.hpp"
#include "flange/math/small_matrix.hpp"
#include "flange/math/tree_solve.hpp"

namespace flange::detail {

/// The cross products the passes need, by the kind of each side: in space two
/// 3-vectors; in the plane normal to K an angular quantity is its component
/// along K (a double) and a linear one its in-plane components (a, b) with
/// e_a × e_b = e_K, so that ω·e_K × l = ω·(−l_b, l_a), r × ω·e_K =
/// ω·(r_b, −r_a), x × y (both in the plane) = (x_a·y_b − x_b·y_a)·e_K and
/// two angular quantities commute. Always inlined (Eigen's cross of two
/// blocks is a call under GCC).
FLANGE_INLINE Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
FLANGE_INLINE double cross(double, double) { return 0; }
FLANGE_INLINE Vec2d cross(double w, const Vec2d& l) { return {-w * l[1], w * l[0]}; }
FLANGE_INLINE Vec2d cross(const Vec2d& r, double w) { return {w * r[1], -w * r[0]}; }
FLANGE_INLINE double cross(const Vec2d& x, const Vec2d& y) { return x[0] * y[1] - x[1] * y[0]; }
FLANGE_INLINE double inner(double x, double y) { return x * y; }
FLANGE_INLINE double inner(const Vec3d& x, const Vec3d& y) { return x.dot(y); }
/// x + y and x − y, a component at a time: Eigen's constructor from a sum of
/// two small vectors is a call under GCC in functions as large as the passes.
FLANGE_INLINE Vec3d plus(const Vec3d& x, const Vec3d& y) { return {x[0] + y[0], x[1] + y[1], x[2] + y[2]}; }
FLANGE_INLINE Vec2d plus(const Vec2d& x, const Vec2d& y) { return {x[0] + y[0], x[1] + y[1]}; }
FLANGE_INLINE double plus(double x, double y) { return x + y; }
FLANGE_INLINE Vec3d minus(const Vec3d& x, const Vec3d& y) { return {x[0] - y[0], x[1] - y[1], x[2] - y[2]}; }
FLANGE_INLINE Vec2d minus(const Vec2d& x, const Vec2d& y) { return {x[0] - y[0], x[1] - y[1]}; }
FLANGE_INLINE double minus(double x, double y) { return x - y; }
/// R·a for an angular quantity: about K in the plane, which R leaves alone.
FLANGE_INLINE Vec3d turn(const Mat3d& R, const Vec3d& a) { return small::mul(R, a); }
FLANGE_INLINE double turn(const Mat2d&, double a) { return a; }
/// R·x for a linear quantity, and R·Qᵀ for two rotations.
FLANGE_INLINE Vec3d rotate(const Mat3d& R, const Vec3d& x) { return small::mul(R, x); }
FLANGE_INLINE Vec2d rotate(const Mat2d& R, const Vec2d& x) { return R * x; }
FLANGE_INLINE Mat3d rotate_nt(const Mat3d& R, const Mat3d& Q) { return small::mul_nt(R, Q); }
FLANGE_INLINE Mat2d rotate_nt(const Mat2d& R, const Mat2d& Q) { return R * Q.transpose(); }
/// T·a and Tᵀ·a for a moment T (in the plane, its entry about K).
FLANGE_INLINE Vec3d times(const Mat3d& T, const Vec3d& a) { return small::mul(T, a); }
FLANGE_INLINE double times(double T, double a) { return T * a; }
FLANGE_INLINE Vec3d transpose_times(const Mat3d& T, const Vec3d& a) {
  return {T(0, 0) * a[0] + T(1, 0) * a[1] + T(2, 0) * a[2], T(0, 1) * a[0] + T(1, 1) * a[1] + T(2, 1) * a[2],
          T(0, 2) * a[0] + T(1, 2) * a[1] + T(2, 2) * a[2]};
}
FLANGE_INLINE double transpose_times(double T, double a) { return T * a; }
/// A moment's trace (in the plane, its entry about K).
FLANGE_INLINE double trace_of(const Mat3d& T) { return T(0, 0) + T(1, 1) + T(2, 2); }
FLANGE_INLINE double trace_of(double T) { return T; }
/// a += b, in space number by number: Eigen's += on a 3 × 3 matrix is a
/// call the compiler may leave out of line (and so out of the passes' AVX2
/// build) where a unit holds much code (the benchmark's chains unit).
FLANGE_INLINE void add_into(Mat3d& a, const Mat3d& b) { small::add_to(a, b); }
FLANGE_INLINE void add_into(Vec3d& a, const Vec3d& b) {  // (a = plus(a, b): 104 more
  for (int i = 0; i < 3; ++i) a[i] += b[i];                // instructions a spatial arm's Jacobian)
}
FLANGE_INLINE void add_into(Vec2d& a, const Vec2d& b) { a += b; }
FLANGE_INLINE void add_into(double& a, double b) { a += b; }

/// A spatial vector in the passes' frame (link 1's at q, or the World's
/// axes at link 1's origin where the loads on links come from dual numbers
/// in the links' motions, local_loads): motion
/// (angular a, linear l) or force (torque a, force l), in 3-D (G = space)
/// or in the plane (G = plane<K>).
template <class G>
struct spatial {
  typename G::ang a;
  typename G::lin l;
  FLANGE_INLINE friend spatial operator+(const spatial& x, const spatial& y) { return {plus(x.a, y.a), plus(x.l, y.l)}; }
  FLANGE_INLINE friend spatial operator-(const spatial& x, const spatial& y) { return {minus(x.a, y.a), minus(x.l, y.l)}; }
  FLANGE_INLINE friend spatial operator*(const spatial& x, double c) { return {x.a * c, x.l * c}; }
  FLANGE_INLINE spatial& operator+=(const spatial& y) {
    add_into(a, y.a);
    add_into(l, y.l);
    return *this;
  }
  FLANGE_INLINE double dot(const spatial& y) const { return inner(a, y.a) + l.dot(y.l); }
};

/// The motion cross product v × w.
template <class G>
FLANGE_INLINE spatial<G> motion_cross(const spatial<G>& v, const spatial<G>& w) {
  return {cross(v.a, w.a), plus(cross(v.a, w.l), cross(v.l, w.a))};
}
/// The force cross product v ×* f.
template <class G>
FLANGE_INLINE spatial<G> force_cross(const spatial<G>& v, const spatial<G>& f) {
  return {plus(cross(v.a, f.a), cross(v.l, f.l)), cross(v.a, f.l)};
}

/// A rigid body's spatial inertia at the passes' fixed point: mass, first moment
/// h = m·c and rotational inertia about that point (in the plane: about K),
/// in the passes' frame.
template <class G>
struct world_inertia {
  double m;
  typename G::lin h;
  typename G::moment I;
  /// I·x: the momentum of motion x.
  FLANGE_INLINE spatial<G> operator*(const spatial<G>& x) const {
    return {plus(times(I, x.a), cross(h, x.l)), minus(x.l * m, cross(h, x.a))};
  }
  FLANGE_INLINE world_inertia& operator+=(const world_inertia& o) {
    m += o.m;
    add_into(h, o.h);
    add_into(I, o.I);
    return *this;
  }
};

/// The sum of B_k over bodies k, where B_k·w = I_k·(v_k × w) − w ×* (I_k·v_k)
/// − v_k ×* (I_k·w). Written out by 3 × 3 blocks (W = ω̃, V = ṽ, H = h̃ for
/// I_k = [I H; −H m]), B_k = X + Xᵀ + [ℓ̃ p̃; p̃ 0] with X = I_k·(v_k×) and
/// (ℓ, p) = I_k·v_k, its right half is zero and its left half is
/// T = I·W − W·I + v·hᵀ + h·vᵀ − 2·(h·v)·1 + ℓ̃ above K = k̃, k = 2·p: B·w
/// reads w's angular part alone. In the plane T is its entry T_KK = −2·(h·v).
template <class G>
struct velocity_coupling {
  typename G::moment T;
  typename G::lin k;
  FLANGE_INLINE velocity_coupling& operator+=(const velocity_coupling& o) {
    add_into(T, o.T);
    add_into(k, o.k);
    return *this;
  }
  /// B·w.
  FLANGE_INLINE spatial<G> operator*(const spatial<G>& w) const { return {times(T, w.a), cross(k, w.a)}; }
  /// The angular part of Bᵀ·s (its linear part is zero).
  FLANGE_INLINE typename G::ang transposed_times(const spatial<G>& s) const {
    return plus(transpose_times(T, s.a), cross(s.l, k));
  }
};

/// The passes' world in 3-D: the scene's quantities as they are.
struct space {
  using ang = Vec3d;
  using lin = Vec3d;
  using moment = Mat3d;  // a rotational inertia
  static ang zero_ang() { return Vec3d::Zero(); }
  static moment zero_moment() { return Mat3d::Zero(); }
  static ang ang_of(const Vec3d& x) { return x; }
  static lin lin_of(const Vec3d& x) { return x; }
  template <class E>
  static Mat3d rotation_of(const E& e) {
    return dense_rotation<double>(e);
  }
  /// A turn about a coordinate axis, none, or a matrix as it is: their
  /// entries set directly. dense_rotation turns each unit vector, and GCC
  /// assembled those columns into pairs through the stack, a number stored
  /// and the pair loaded back at once, which the processor cannot forward
  /// from the store (the spatial arm's Jacobian 524 → 464 ns, the one-link chain
  /// of a run-time axis 77 → 53 ns, two floating legs 1,381 → 1,249 ns:
  /// tools/probes/small_jacobians.cpp, seven runs in turns; the same
  /// numbers).
  template <int I>
  static Mat3d rotation_of(const coordinate_rotation<double, I>& e) {
    return to_matrix<double>(e);
  }
  static Mat3d rotation_of(identity_rotation) { return Mat3d::Identity(); }
  static Mat3d rotation_of(const Mat3d& e) { return e; }
  /// A link's inertia (m, h, I in link coordinates about the link origin)
  /// where the passes' frame is the link's own: as it is.
  FLANGE_INLINE static world_inertia<space> at_link(const rigid_inertia<double>& b) { return {b.m, b.h, b.I}; }
  /// The same at the link's pose in the passes' frame (R: link → that
  /// frame, r: its origin): R·I·Rᵀ, shifted
  /// to the fixed point by the parallel-axis terms of a body with first
  /// moment R·h, I − g·rᵀ − r·gᵀ + 2·(r·g)·1 with g = m·r/2 + R·h. Column by
  /// column, each column a vector of four numbers (GCC's vector extension:
  /// two SSE2 registers, or one AVX2 register in the passes' AVX2 build);
  /// each entry is the same products and sums, in the same order, as when
  /// written out number by number, and the upper triangle is mirrored (the
  /// result is symmetric). Against the entries written out one by one, in
  /// about as many instructions: the typed 2-link chain's Jacobian 291 → 260
  /// ns, a floating base with one leg 827 → 802 ns, the spatial arm 511 →
  /// 501 ns (tools/probes/small_jacobians.cpp, nine runs in turns, medians).
  FLANGE_INLINE static world_inertia<space> to_world(const rigid_inertia<double>& b, const Mat3d& R, const Vec3d& r) {
    using v4 = double __attribute__((vector_size(32)));
    const double *Rn = R.data(), *In = b.I.data();
    const v4 R0{Rn[0], Rn[1], Rn[2], 0.0}, R1{Rn[3], Rn[4], Rn[5], 0.0}, R2{Rn[6], Rn[7], Rn[8], 0.0};
    const v4 rv{r[0], r[1], r[2], 0.0};
    const v4 Rh = R0 * b.h[0] + R1 * b.h[1] + R2 * b.h[2];
    const v4 A0 = R0 * In[0] + R1 * In[1] + R2 * In[2], A1 = R0 * In[3] + R1 * In[4] + R2 * In[5],
             A2 = R0 * In[6] + R1 * In[7] + R2 * In[8];
    const v4 g = 0.5 * b.m * rv + Rh;
    const double d = 2 * (r[0] * g[0] + r[1] * g[1] + r[2] * g[2]);
    v4 c[3];
    for (int j = 0; j < 3; ++j) {
      const v4 e{j == 0 ? d : 0.0, j == 1 ? d : 0.0, j == 2 ? d : 0.0, 0.0};
      c[j] = A0 * R(j, 0) + A1 * R(j, 1) + A2 * R(j, 2) - (g * r[j] + rv * g[j]) + e;
    }
    Mat3d I;
    small::for_upper([&](int i, int j) FLANGE_INLINE_LAMBDA { I(j, i) = I(i, j) = c[j][i]; });
    const v4 h = Rh + b.m * rv;
    return {b.m, {h[0], h[1], h[2]}, I};
  }
  /// B of a body of inertia I moving at v, with its momentum h = I·v:
  /// T = P + Pᵀ + v·hᵀ + h·vᵀ − 2·(h·v)·1 + ℓ̃ with P = I·ω̃ (I·W − W·I = P + Pᵀ
  /// for a symmetric I), its symmetric part on the upper triangle.
  FLANGE_INLINE static velocity_coupling<space> coupling_of(const world_inertia<space>& I, const spatial<space>& v,
                                                            const spatial<space>& h) {
    const Vec3d& w = v.a;
    // P = I·ω̃: column j of ω̃ is ω × e_j.
    Mat3d P;
    for (int i = 0; i < 3; ++i) {
      P(i, 0) = I.I(i, 1) * w[2] - I.I(i, 2) * w[1];
      P(i, 1) = I.I(i, 2) * w[0] - I.I(i, 0) * w[2];
      P(i, 2) = I.I(i, 0) * w[1] - I.I(i, 1) * w[0];
    }
    const double hv = 2 * (I.h[0] * v.l[0] + I.h[1] * v.l[1] + I.h[2] * v.l[2]);
    Mat3d T;
    small::for_upper([&](int i, int j) FLANGE_INLINE_LAMBDA {
      T(j, i) = T(i, j) = P(i, j) + P(j, i) + v.l[i] * I.h[j] + I.h[i] * v.l[j] - (i == j ? hv : 0.0);
    });
    T(0, 1) -= h.a[2];
    T(1, 0) += h.a[2];
    T(0, 2) += h.a[1];
    T(2, 0) -= h.a[1];
    T(1, 2) -= h.a[0];
    T(2, 1) += h.a[0];
    return {T, {2 * h.l[0], 2 * h.l[1], 2 * h.l[2]}};
  }
  /// A body's inertia as the 6 × 6 matrix [I h̃; h̃ᵀ m·1] that I·x applies.
  static Eigen::Matrix<double, 6, 6> matrix_of(const world_inertia<space>& b) {
    Eigen::Matrix<double, 6, 6> A;
    Mat3d H;
    H << 0, -b.h[2], b.h[1], b.h[2], 0, -b.h[0], -b.h[1], b.h[0], 0;
    A << b.I, H, H.transpose(), b.m * Mat3d::Identity();
    return A;
  }
};

/// The passes' world in the plane normal to axis K of a planar scene
/// (dynamics/algebra.hpp's planar_axis): motion and force in se(2), which
/// the cross products close over. What it drops (offsets, first moments and
/// gravity along K, the inertia's other entries) changes no q̈ and so none of
/// its derivatives.
template <int K>
struct plane {
  static constexpr int A = (K + 1) % 3, B = (K + 2) % 3;
  using ang = double;
  using lin = Vec2d;
  using moment = double;  // a rotational inertia: its entry about K
  static ang zero_ang() { return 0; }
  static moment zero_moment() { return 0; }
  static ang ang_of(const Vec3d& x) { return x[K]; }
  static lin lin_of(const Vec3d& x) { return {x[A], x[B]}; }
  /// A rotation about K as the 2 × 2 matrix of its in-plane block.
  template <class E>
  static Mat2d rotation_of(const E& e) {
    const Vec3d c = rot(e, to_svec(Vec3d(Vec3d::Unit(A)))).dense();
    Mat2d R;
    R << c[A], -c[B], c[B], c[A];
    return R;
  }
  FLANGE_INLINE static world_inertia<plane> at_link(const rigid_inertia<double>& b) {
    return {b.m, lin_of(b.h), b.I(K, K)};
  }
  FLANGE_INLINE static world_inertia<plane> to_world(const rigid_inertia<double>& b, const Mat2d& R, const Vec2d& r) {
    const Vec2d Rh = R * lin_of(b.h);
    return {b.m, Rh + b.m * r, b.I(K, K) + b.m * r.squaredNorm() + 2 * r.dot(Rh)};
  }
  FLANGE_INLINE static velocity_coupling<plane> coupling_of(const world_inertia<plane>& I, const spatial<plane>& v,
                                                            const spatial<plane>& h) {
    return {-2 * I.h.dot(v.l), 2 * h.l};
  }
  /// A body's inertia as the 3 × 3 matrix that I·x applies.
  static Eigen::Matrix3d matrix_of(const world_inertia<plane>& b) {
    Eigen::Matrix3d A;
    A << b.I, -b.h[1], b.h[0], -b.h[1], b.m, 0, b.h[0], 0, b.m;
    return A;
  }
};

/// A node's column s in the passes' frame by its shape, where the passes
/// know it: a turn c·e_k about coordinate axis k through the frame's origin,
/// s = (c·e_k, 0) (the shape is k: the rotation rates of a ball at link 1,
/// in link 1's axes), a translation s = (0, l)
/// (translation_column), or any column (any_column). The products below with
/// such a column leave out the terms its zeros make zero: the same numbers
/// (but for the sign of a zero).
inline constexpr int any_column = -1, translation_column = -2;

/// (c·e_k) × x: each k made from registers (a number stored at a place
/// known only at run time, and read back as part of a pair, waits for the
/// store to land).
FLANGE_INLINE Vec3d axis_cross(int k, double c, const Vec3d& x) {
  if (k == 0) return {0, -c * x[2], c * x[1]};
  if (k == 1) return {c * x[2], 0, -c * x[0]};
  return {-c * x[1], c * x[0], 0};
}

/// s·x for column s of shape k.
template <class G>
FLANGE_INLINE double column_dot(int k, const spatial<G>& s, const spatial<G>& x) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) return s.a[k] * x.a[k];
    if (k == translation_column) return s.l.dot(x.l);
  }
  return s.dot(x);
}
/// The angular parts' product z·s_a.
template <class G>
FLANGE_INLINE double column_angular_dot(int k, const typename G::ang& z, const spatial<G>& s) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) return z[k] * s.a[k];
    if (k == translation_column) return 0.0;
  }
  return inner(z, s.a);
}
/// I·s.
template <class G>
FLANGE_INLINE spatial<G> inertia_times_column(int k, const world_inertia<G>& I, const spatial<G>& s) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) {
      const double c = s.a[k];
      return {I.I.col(k) * c, axis_cross(k, c, I.h)};
    }
    if (k == translation_column) return {cross(I.h, s.l), s.l * I.m};
  }
  return I * s;
}
/// B·s.
template <class G>
FLANGE_INLINE spatial<G> coupling_times_column(int k, const velocity_coupling<G>& B, const spatial<G>& s) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) {
      const double c = s.a[k];
      return {B.T.col(k) * c, -axis_cross(k, c, B.k)};
    }
    if (k == translation_column) return {Vec3d::Zero(), Vec3d::Zero()};
  }
  return B * s;
}
/// The angular part of Bᵀ·s.
template <class G>
FLANGE_INLINE typename G::ang coupling_transposed_times_column(int k, const velocity_coupling<G>& B,
                                                              const spatial<G>& s) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) return B.T.row(k).transpose() * s.a[k];
    if (k == translation_column) return cross(s.l, B.k);
  }
  return B.transposed_times(s);
}
/// s × v.
template <class G>
FLANGE_INLINE spatial<G> column_motion_cross(int k, const spatial<G>& s, const spatial<G>& v) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) return {axis_cross(k, s.a[k], v.a), axis_cross(k, s.a[k], v.l)};
    if (k == translation_column) return {Vec3d::Zero(), cross(s.l, v.a)};
  }
  return motion_cross(s, v);
}
/// (0, s_a × x): s × (0, x) for a column s whose own translation is left out.
template <class G>
FLANGE_INLINE spatial<G> column_angular_cross(int k, const spatial<G>& s, const typename G::lin& x) {
  if constexpr (std::is_same_v<G, space>)
    if (k >= 0) return {G::zero_ang(), axis_cross(k, s.a[k], x)};
  return {G::zero_ang(), cross(s.a, x)};
}
/// x + s·c.
template <class G>
FLANGE_INLINE spatial<G> plus_column(int k, const spatial<G>& x, const spatial<G>& s, double c) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) {
      spatial<G> r = x;
      r.a[k] += s.a[k] * c;
      return r;
    }
    if (k == translation_column) return {x.a, plus(x.l, s.l * c)};
  }
  return x + s * c;
}
/// s ×* f.
template <class G>
FLANGE_INLINE spatial<G> column_force_cross(int k, const spatial<G>& s, const spatial<G>& f) {
  if constexpr (std::is_same_v<G, space>) {
    if (k >= 0) return {axis_cross(k, s.a[k], f.a), axis_cross(k, s.a[k], f.l)};
    if (k == translation_column) return {cross(s.l, f.l), Vec3d::Zero()};
  }
  return force_cross(s, f);
}

/// The geometry a scene's passes run in: its plane if it is planar, else space.
template <class S>
using geometry_t =
    std::conditional_t<(planar_axis<S>() >= 0), plane<(planar_axis<S>() >= 0 ? planar_axis<S>() : 2)>, space>;

/// A spatial vector's numbers, angular first: six in space, three in the plane.
FLANGE_INLINE std::array<double, 6> numbers(const spatial<space>& x) {
  return {x.a[0], x.a[1], x.a[2], x.l[0], x.l[1], x.l[2]};
}
template <int K>
FLANGE_INLINE std::array<double, 3> numbers(const spatial<plane<K>>& x) {
  return {x.a, x.l[0], x.l[1]};
}

/// Whether joint type J is one the analytic derivatives handle as one node:
/// one rate and its column fixed in its link.
template <class J>
constexpr bool one_axis_joint() {
  return J::nq == 1 && J::nv == 1 && fixed_subspace<J>;
}

/// Whether joint type J, connected Dir, is a ball the analytic derivatives
/// handle (core/joint.hpp, ball_rates: a Spherical, a FreeMotion): its
/// translations along the parent's axes are nodes of one rate each, and its
/// three rotation rates, ω in the link, a group of nodes whose columns all
/// turn with each of them. It transmits nothing of its own.
template <class J, int Dir>
constexpr bool ball_joint() {
  if constexpr (requires { requires J::ball_rates; }) {
    return Dir > 0 && !has_generalized_force<J>;
  } else {
    return false;
  }
}

/// Whether joint type J, connected Dir, is one the analytic derivatives
/// handle as one-rate nodes in a row (core/joint.hpp, sequential_rates: a
/// Universal, a Cylindrical, a Planar), connected frame_a toward the World
/// or, where its columns commute (commuting_rates: a Cylindrical), either
/// way round: each rate's column is fixed in the frame the rates before it
/// have moved, as a one-axis joint's in a massless link between them. It
/// transmits nothing of its own.
template <class J, int Dir>
constexpr bool sequential_joint() {
  if constexpr (requires { requires J::sequential_rates; }) {
    constexpr bool commuting = requires { requires J::commuting_rates; };
    return (Dir > 0 || commuting) && J::nq == J::nv && !has_generalized_force<J>;
  } else {
    return false;
  }
}

/// Whether some force element acts on a link (not only on the World).
template <class S>
constexpr bool has_link_loads() {
  for (int L = 1; L < S::tree.n_links; ++L)
    if (load_flags<S>::value.torque[L]) return true;
  return false;
}

/// Whether link L + 1's joint is a ball (above), by link.
template <class S>
inline constexpr auto ball_links = [] {
  std::array<bool, S::tree.n_links> r{};
  [&]<int... L>(std::integer_sequence<int, L...>) {
    ((r[L + 1] = ball_joint<typename link_info<S, L + 1>::joint_type, link_info<S, L + 1>::dir>()), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  return r;
}();

/// Whether the passes below take the scene's tree (its loops' cut joints
/// aside): every joint one they are written for, connected frame_a toward
/// the World.
template <class S>
constexpr bool analytic_tree() {
  if constexpr (!walkable<S> || S::tree.n_links < 2) {
    return false;
  } else {
    return []<int... L>(std::integer_sequence<int, L...>) {
      return ((one_axis_joint<typename link_info<S, L + 1>::joint_type>() || ball_links<S>[L + 1] ||
               sequential_joint<typename link_info<S, L + 1>::joint_type, link_info<S, L + 1>::dir>()) &&
              ...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  }
}

/// Whether the scene's ∂v̇/∂x comes from analytic_derivatives (above): a
/// tree they take, with no loop.
template <class S>
constexpr bool analytic_derivatives() {
  return S::tree.n_cuts == 0 && analytic_tree<S>();
}

/// The passes' nodes: one per rate, link by link (parents first) and each
/// link's rates in order, node 0 the World. A node's parent is the node
/// before it (its link's previous rate, or its parent link's last); a ball's
/// rotation nodes all take the velocity and acceleration of the node before
/// the ball (vparent) and form one group (group: its first node; else the
/// node itself). A link's body is at its last node.
template <class S>
struct derivative_nodes {
  static constexpr int NL = S::tree.n_links, NN = S::n_v + 1;
  struct table_t {
    std::array<int, NN> link{}, parent{}, vparent{}, rate{}, group{};
    std::array<int, NN> index{};  ///< its rate's place among its link's
    std::array<bool, NN> ball{};  ///< a ball's rotation node
    std::array<int, NL> last{};
  };
  static constexpr table_t table = [] {
    table_t r{};
    int n = 1;
    for (int L = 1; L < NL; ++L) {
      const int J = S::tree.link_joint[L], nv = S::table.nv[J], v0 = S::tree.v_offset[J];
      const int ball_from = ball_links<S>[L] ? nv - 3 : nv;  // its first rotation rate
      int prev = r.last[S::tree.link_parent[L]], before_ball = prev;
      for (int k = 0; k < nv; ++k, ++n) {
        if (k == ball_from) before_ball = prev;
        r.link[n] = L;
        r.index[n] = k;
        r.rate[n] = v0 + k;
        r.parent[n] = prev;
        r.vparent[n] = k >= ball_from ? before_ball : prev;
        r.group[n] = k >= ball_from ? n - (k - ball_from) : n;
        r.ball[n] = k >= ball_from;
        prev = n;
      }
      r.last[L] = n - 1;
    }
    return r;
  }();
  /// Whether every node's parent is the node before it.
  static constexpr bool chain = [] {
    for (int n = 1; n < NN; ++n)
      if (table.parent[n] != n - 1) return false;
    return true;
  }();
};

/// Whether part Lin (its linear part, else its angular one) of column K of
/// link motion M is zero by type (a typed zero).
template <class M, int K, bool Lin>
constexpr bool zero_column_part() {
  using C = decltype(std::declval<const M&>().template col<K>());
  using A = std::remove_cvref_t<std::conditional_t<Lin, decltype(std::declval<C>().lin), decltype(std::declval<C>().ang)>>;
  if constexpr (is_svec<A>) return A::mask == 0;
  else return false;
}
template <class M, bool Lin, int... K>
constexpr unsigned zero_column_parts(std::integer_sequence<int, K...>) {
  return ((unsigned(zero_column_part<M, K, Lin>()) << K) | ... | 0u);
}
/// The axis k of column K of link motion M where its angular part is along
/// a coordinate axis by type (c·e_k), else −1.
template <class M, int K>
constexpr int axial_column_part() {
  using C = decltype(std::declval<const M&>().template col<K>());
  using A = std::remove_cvref_t<decltype(std::declval<C>().ang)>;
  if constexpr (is_svec<A>) return A::mask == 1 ? 0 : A::mask == 2 ? 1 : A::mask == 4 ? 2 : -1;
  else return -1;
}
template <class M, int... K>
constexpr std::array<int, 8> axial_column_parts(std::integer_sequence<int, K...>) {
  std::array<int, 8> r{};
  ((r[K] = axial_column_part<M, K>()), ...);
  return r;
}

/// Which parts of the nodes' columns are zero by type: no_ang[n] (a
/// translation: a Prismatic's, a ball's or a Cylindrical's) and no_lin[n] (a
/// rotation about an axis through the link's origin: a Revolute's, a ball's);
/// and axis[n], the coordinate axis k of a column whose angular part is
/// c·e_k by type in its link's coordinates (a ball's rotation rates, a
/// Revolute about a typed axis), else −1.
template <class S>
struct column_parts {
  using nodes = derivative_nodes<S>;
  static constexpr auto table = [] {
    using motions = decltype(link_motions<spatial_algebra, double, true>(std::declval<const S&>(),
                                                                        std::declval<const double*>()));
    std::array<unsigned, S::tree.n_links> ang{}, lin{};  // bit k: column k of link L's joint
    std::array<std::array<int, 8>, S::tree.n_links> axial{};
    [&]<int... L>(std::integer_sequence<int, L...>) {
      ((ang[L + 1] = zero_column_parts<std::tuple_element_t<L, motions>, false>(
            std::make_integer_sequence<int, link_info<S, L + 1>::nv>{}),
        lin[L + 1] = zero_column_parts<std::tuple_element_t<L, motions>, true>(
            std::make_integer_sequence<int, link_info<S, L + 1>::nv>{}),
        axial[L + 1] = axial_column_parts<std::tuple_element_t<L, motions>>(
            std::make_integer_sequence<int, link_info<S, L + 1>::nv>{})),
       ...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
    struct r_t {
      std::array<bool, nodes::NN> no_ang{}, no_lin{};
      std::array<int, nodes::NN> axis{};
    } r;
    r.axis[0] = -1;
    for (int n = 1; n < nodes::NN; ++n) {
      const int L = nodes::table.link[n], k = nodes::table.index[n];
      r.no_ang[n] = (ang[L] >> k) & 1u;
      r.no_lin[n] = (lin[L] >> k) & 1u;
      r.axis[n] = axial[L][k];
    }
    return r;
  }();
};

/// Which nodes move by translation alone: node n's column has no angular
/// part (column_parts) and neither has any node above it (node 0, the
/// World, is one). Such a node's velocity, acceleration and their changes
/// have no angular part, so that for a node whose velocity parent V is one,
/// u = s × v_V and ψ = s × a_V − u × v_V read the linear parts alone (one
/// cross product each; none where the node is one itself: u = ψ = 0, and so
/// are its pairs' u and ψ terms).
template <class S>
inline constexpr auto translating_nodes = [] {
  using nodes = derivative_nodes<S>;
  std::array<bool, nodes::NN> r{};
  r[0] = true;
  for (int n = 1; n < nodes::NN; ++n) r[n] = column_parts<S>::table.no_ang[n] && r[nodes::table.parent[n]];
  return r;
}();

/// Whether acceleration_derivatives solves with M's articulated-body factor
/// (math/chain_solve.hpp) rather than with the triangular solves of its
/// LTDL factor (math/tree_solve.hpp): on a chain of at least 4·C nodes
/// (C numbers a spatial vector: 24 nodes in space, 12 in the plane), where
/// its 4·C multiply-adds a node and column are fewer than their N.
template <class S>
constexpr bool articulated_solve() {
  constexpr int C = std::is_same_v<geometry_t<S>, space> ? 6 : 3;
  return derivative_nodes<S>::chain && S::n_v >= 4 * C;
}

/// Each node's ancestors other than the World, nearest first, as M's
/// indices (node − 1): up[k][0 … depth[k] − 1]. The leaves-first factor
/// of M updates, for node k, the entries of every pair of them.
template <class S>
struct factor_ancestry {
  static constexpr int NN = S::n_v + 1;
  struct table_t {
    std::array<std::array<int, NN>, NN> up{};
    std::array<int, NN> depth{};
  };
  static constexpr table_t table = [] {
    table_t t{};
    for (int k = 1; k < NN; ++k)
      for (int i = derivative_nodes<S>::table.parent[k]; i != 0; i = derivative_nodes<S>::table.parent[i])
        t.up[k][t.depth[k]++] = i - 1;
    return t;
  }();
  static constexpr const auto& up = table.up;
  static constexpr const auto& depth = table.depth;
  /// Pair P, row by row, of the triangle a ≤ b < Depth: (a, b).
  template <int Depth, int P>
  static constexpr std::pair<int, int> pair = [] {
    int a = 0, p = P;
    while (p >= Depth - a) p -= Depth - a++;
    return std::pair<int, int>{a, a + p};
  }();
  /// The updates of the whole factor: Σ over k of depth·(depth + 1)/2.
  static constexpr int updates = [] {
    int u = 0;
    for (int k = 1; k < NN; ++k) u += table.depth[k] * (table.depth[k] + 1) / 2;
    return u;
  }();
};

/// The most updates a tree's factor of M is written out for
/// (factor_ancestry): up to it each update's place is a constant; beyond
/// it the code would grow past what it saves.
inline constexpr int unrolled_factor_updates = 600;

/// Whether acceleration_derivatives factors M written out (factor_ancestry)
/// rather than in loops: a tree's, which would walk its ancestors, and a
/// chain's from four nodes on, whose dense loops are mostly their own
/// overhead at these sizes (the planar 7-link chain 560 → 499 ns a
/// Jacobian, the chain of joints of rates in series, nine nodes, 1,821 →
/// 1,573 ns). On fewer nodes the call costs more than the loops (the gantry
/// crane 71 against 80 ns; docs/performance.md, "The Jacobian").
template <class S>
constexpr bool unrolled_factor() {
  return factor_ancestry<S>::updates <= unrolled_factor_updates &&
         (!derivative_nodes<S>::chain || S::n_v >= 4);
}

/// M = Lᵀ·D·L in place, leaves first (Featherstone's LTDL: L has the tree's
/// zeros), held as math/tree_solve.hpp reads it (U = D·L below the diagonal,
/// L above it, inv[k] = 1 / D_k), written out from factor_ancestry: every
/// update's place a constant. The same products in the same order as the
/// loops of acceleration_derivatives_passes that walk the ancestors.
/// Returns 0, or the node whose pivot is at or below tol of its yardstick
/// (M(k − 1, k − 1) left as it was). Compiled once, not in each of the
/// passes' two builds: written out, it is a good part of their compile time.
template <class S>
[[gnu::noinline]] int factor_tree_written_out(Eigen::Matrix<double, S::n_v, S::n_v>& M,
                                              const std::array<double, S::n_v>& yard, double tol,
                                              std::array<double, S::n_v + 1>& inv) {
  constexpr int NN = S::n_v + 1;
  using anc = factor_ancestry<S>;
  int failed = 0;
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    return ([&]() FLANGE_INLINE_LAMBDA {
      constexpr int k = NN - 1 - K, depth = anc::depth[k];
      if (!(M(k - 1, k - 1) > tol * yard[k - 1])) [[unlikely]] {
        failed = k;
        return false;
      }
      const double e = inv[k] = 1 / M(k - 1, k - 1);
      std::array<double, depth> c;  // row k of L
      [&]<int... A>(std::integer_sequence<int, A...>) FLANGE_INLINE_LAMBDA {
        ((c[A] = M(anc::up[k][A], k - 1) = M(k - 1, anc::up[k][A]) * e), ...);
      }(std::make_integer_sequence<int, depth>{});
      // Pair P of the triangle a ≤ b < depth, row by row: L(k, a)·U(k, b).
      [&]<int... P>(std::integer_sequence<int, P...>) FLANGE_INLINE_LAMBDA {
        ((M(anc::up[k][anc::template pair<depth, P>.first], anc::up[k][anc::template pair<depth, P>.second]) -=
          c[anc::template pair<depth, P>.first] * M(k - 1, anc::up[k][anc::template pair<depth, P>.second])),
         ...);
      }(std::make_integer_sequence<int, depth * (depth + 1) / 2>{});
      return true;
    }() && ...);
  }(std::make_integer_sequence<int, NN - 1>{});
  return failed;
}

/// The nodes' tree as math/tree_solve.hpp reads it.
template <class S>
struct node_parents {
  static constexpr const auto& parent = derivative_nodes<S>::table.parent;
};
template <class S>
using node_runs = tree_runs<node_parents<S>>;

/// The rate of row r of acceleration_derivatives' result: node r + 1's.
template <class S>
inline constexpr auto derivative_row_rate = [] {
  std::array<int, S::n_v> r{};
  for (int n = 1; n <= S::n_v; ++n) r[n - 1] = derivative_nodes<S>::table.rate[n];
  return r;
}();

/// The most nodes a tree may have for the passes over its nodes to be
/// written out node by node (over_nodes): each node's step then compiled
/// with n a constant, so that its parent, rate and kind are constants and its
/// pair loops (over its ancestors) unroll. The backward passes always; the
/// forward ones in the plane alone: in space, written out, they ran slower
/// for fewer instructions. On larger trees it costs more compile time than
/// it saves (docs/performance.md, "The Jacobian", has the figures).
inline constexpr int written_out_nodes = 4;

/// step(n) for the nodes n = 1 … NN − 1, parents first, or with
/// ChildrenFirst the other way: written out (each n a constant) where
/// WriteOut and the tree has up to written_out_nodes, else a loop.
template <int NN, bool ChildrenFirst, bool WriteOut = true, class Step>
FLANGE_INLINE void over_nodes(Step&& step) {
  if constexpr (WriteOut && NN - 1 <= written_out_nodes)
    static_for<NN - 1>([&](auto k) FLANGE_INLINE_LAMBDA { step(ChildrenFirst ? NN - 1 - int(k) : int(k) + 1); });
  else if constexpr (ChildrenFirst)
    for (int n = NN - 1; n >= 1; --n) step(n);
  else
    for (int n = 1; n < NN; ++n) step(n);
}

/// The coordinate of each rate where it is the rate's own (q̇ = v: a joint
/// of one rate, rates in series, a ball's translations), −1 for a ball's
/// rotation rates, whose quaternion moves with all three.
template <class S>
inline constexpr auto rate_coordinate = [] {
  std::array<int, S::n_v> r{};
  [&]<int... L>(std::integer_sequence<int, L...>) {
    (
        [&] {
          using LI = link_info<S, L + 1>;
          using J = typename LI::joint_type;
          int plain = J::nv;
          if constexpr (ball_links<S>[L + 1]) plain = J::quaternion_at;
          for (int k = 0; k < J::nv; ++k) r[LI::v + k] = k < plain ? LI::q + k : -1;
        }(),
        ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  return r;
}();

/// The links whose joint's force reads the state (a drive τ(t, x)), in link
/// order: link[0 … count − 1].
template <class S>
struct state_reading_links {
  static constexpr int NL = S::tree.n_links;
  static constexpr auto table = [] {
    std::pair<std::array<int, NL>, int> r{};
    [&]<int... L>(std::integer_sequence<int, L...>) {
      ((force_reads_state<typename link_info<S, L + 1>::joint_type>() ? (r.first[r.second++] = L + 1, 0) : 0), ...);
    }(std::make_integer_sequence<int, NL - 1>{});
    return r;
  }();
  static constexpr int count = table.second;
  static constexpr const std::array<int, NL>& link = table.first;
  static constexpr int index_of(int L) {
    int k = 0;
    while (table.first[k] != L) ++k;
    return k;
  }
};

/// A vector of dual numbers' values (c = −1) or their derivatives in direction c.
template <int K>
FLANGE_INLINE Vec3d lane(const Vec3<dual<double, K>>& x, int c) {
  if (c < 0) return {x[0].v, x[1].v, x[2].v};
  return {x[0].d[c], x[1].d[c], x[2].d[c]};
}

/// A load on a link (torque n about its origin and force f, link
/// coordinates) as a wrench at the passes' fixed point, the link at (R, r).
template <class G, class Rot, class Lin>
FLANGE_INLINE spatial<G> world_wrench(const Rot& R, const Lin& r, const Vec3d& n, const Vec3d& f) {
  const typename G::lin Rf = R * G::lin_of(f);
  return {turn(R, G::ang_of(n)) + cross(r, Rf), Rf};
}

/// Whether the loads of every force element that acts on a link are a
/// function of its own links' motions and the time alone (none reads the
/// joint state: element_reads_state), in 3-D: their derivatives then come
/// from dual numbers in those links' motions (local_lanes), 12 per link and
/// one for the time, rather than in every direction of the state.
template <class S>
constexpr bool local_loads() {
  if constexpr (!std::is_same_v<geometry_t<S>, space>) {
    return false;
  } else {
    return []<int... C>(std::integer_sequence<int, C...>) {
      return (true && ... && [] {
        using Comp = typename S::template component_type<C>;
        if constexpr (Comp::kind == role::force) {
          if constexpr (force_acts<S, C>()) return !element_reads_state<Comp>();
          else return true;
        } else {
          return true;
        }
      }());
    }(std::make_integer_sequence<int, S::n_components>{});
  }
}

/// The links other than the World that force element C's frames sit on,
/// each once: link[0 … count − 1].
template <class S, int C>
struct element_links {
  static constexpr auto frame_links = force_links<S, C>();
  static constexpr auto table = [] {
    std::pair<std::array<int, frame_links.size()>, int> r{};
    for (int k = 0; k < int(frame_links.size()); ++k) {
      bool seen = frame_links[k] == 0;
      for (int j = 0; j < r.second; ++j) seen = seen || r.first[j] == frame_links[k];
      if (!seen) r.first[r.second++] = frame_links[k];
    }
    return r;
  }();
  static constexpr int count = table.second;
  static constexpr const auto& link = table.first;
  /// The block of link L among them (0 for the World's frames, which read none).
  static constexpr int block_of(int L) {
    for (int j = 0; j < count; ++j)
      if (table.first[j] == L) return j;
    return 0;
  }
};

/// A link's pose and motion (velocity in link coordinates) as dual numbers
/// in 12 directions from lane b: the link turned by ε_θ and moved by ε_p (a
/// twist at the passes' fixed point, world coordinates), then its twist V
/// there changed by (δω, δv). Rw: link → world; r: its origin from the fixed
/// point; o: the fixed point from the World's origin.
template <class D, int b>
link_pose<D, velocity_in::link> local_lanes(const Mat3d& Rw, const Vec3d& r, const Vec3d& o,
                                            const spatial<space>& V) {
  // ∂/∂ε_θk: e_k × (each column of Rw, and r), turns[k][j] (j = 3: r).
  std::array<std::array<Vec3d, 4>, 3> turns;
  for (int k = 0; k < 3; ++k) {
    const Vec3d e = Vec3d::Unit(k);
    for (int j = 0; j < 3; ++j) turns[k][j] = cross(e, Vec3d(Rw.col(j)));
    turns[k][3] = cross(e, r);
  }
  // Each made whole (D::with_lanes), not a lane at a time.
  Mat3<D> Rd;
  Vec3<D> rd, w, vo;
  for (int i = 0; i < 3; ++i) {
    rd[i] = D::with_lanes(r[i], [&](int l) {
      const int k = l - b;
      return k >= 0 && k < 3 ? turns[k][3][i] : k == 3 + i ? 1.0 : 0.0;
    });
    w[i] = D::variable(V.a[i], b + 6 + i);
    vo[i] = D::variable(V.l[i], b + 9 + i);
    for (int j = 0; j < 3; ++j)
      Rd(i, j) = D::with_lanes(Rw(i, j), [&](int l) {
        const int k = l - b;
        return k >= 0 && k < 3 ? turns[k][j][i] : 0.0;
      });
  }
  link_pose<D, velocity_in::link> P;
  P.R = Rd.transpose();
  P.r = rd + o.template cast<D>();
  P.w = P.R * w;
  P.v = P.R * (vo + w.cross(rd));
  return P;
}

/// The matrix acceleration_derivatives fills: a row per rate, in link order,
/// its 2·n_v + 1 columns padded (with zeros) to math/tree_solve.hpp's row.
template <class S>
using derivative_rows = Eigen::Matrix<double, S::n_v, tree_solve_row(2 * S::n_v + 1), Eigen::RowMajor>;

/// ∂v̇/∂q, ∂v̇/∂v and ∂v̇/∂t at (t, q, v) as the columns of out, and v̇ itself
/// into vdot when given. Columns in rate order: first the directions of q,
/// one per rate (a ball's rotation rates: its link turned about its own axes,
/// Q moving by ½·Q ⊗ (δ, 0); simulate/jacobian.hpp turns these into the
/// quaternion's four), then v, then t; row r is rate derivative_row_rate<S>[r].
/// With force given, those generalized forces (by rate) join Q, held fixed
/// in x: a loop's constraint forces Gᵀ·λ at the loop solve's λ, which make
/// v̇ the constrained accelerations and out M⁻¹·(∂Q − ∂ID) at them
/// (simulate/jacobian.hpp adds the derivative of Gᵀ itself).
/// Returns the pivot of M that failed (index ≥ 0: out and vdot are not
/// written; index is its rate), as the mass-matrix solve reports it.
/// Articulated: M⁻¹ by its articulated-body factor (math/chain_solve.hpp, a
/// chain's), else by its LTDL factor; the two agree to round-off.
/// Always inlined into the two functions that compile it (below): one for
/// the instructions every x86-64 runs, one for AVX2.
template <class S, bool Articulated>
[[gnu::always_inline]] inline pivot_report<double> acceleration_derivatives_passes(const S& scene, double t,
                                                                                  const double* q, const double* v,
                                                                                  derivative_rows<S>& out,
                                                                                  double* vdot, const double* force = nullptr) {
  static_assert(analytic_tree<S>());
  constexpr int NL = S::tree.n_links, N = S::n_v, NN = N + 1;
  using nodes = derivative_nodes<S>;
  constexpr auto link_parent = [] {
    std::array<int, NL> p{};
    for (int L = 0; L < NL; ++L) p[L] = S::tree.link_parent[L];
    return p;
  }();
  constexpr auto parent = nodes::table.parent;
  constexpr auto vparent = nodes::table.vparent;
  constexpr auto rate = nodes::table.rate;
  constexpr auto node_link = nodes::table.link;
  constexpr auto last = nodes::table.last;
  constexpr auto translating = translating_nodes<S>;
  static constexpr const auto& parts = column_parts<S>::table;  // static: the lambdas below take it uncaptured
  constexpr bool balls = [] {
    for (int L = 1; L < NL; ++L)
      if (ball_links<S>[L]) return true;
    return false;
  }();
  constexpr bool one_node_links = N == NL - 1;  // every link a node (no ball, no rates in series)

  // Each link's motion at q, densified: E (parent → link), p (its origin in
  // the parent's coordinates); each node's column (link coordinates).
  using G = geometry_t<S>;
  constexpr bool in_plane = !std::is_same_v<G, space>;  // the passes in a plane (over_nodes)
  using Rot = decltype(G::rotation_of(std::get<0>(link_motions<spatial_algebra, double, true>(scene, q)).E()));
  std::array<Rot, NL> E, R;
  std::array<typename G::lin, NL> p, r;
  std::array<spatial<G>, NN> col;
  {
    const auto motions = link_motions<spatial_algebra, double, true>(scene, q);
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value;
      constexpr int nv = link_info<S, L>::nv, first = nodes::table.last[L] - nv + 1;
      const auto& m = std::get<L - 1>(motions);
      E[L] = G::rotation_of(m.E());
      p[L] = G::lin_of(m.p.dense());
      static_for<nv>([&](auto k) {
        const auto c = m.template col<decltype(k)::value>();
        col[first + k] = {G::ang_of(c.ang.dense()), G::lin_of(c.lin.dense())};
      });
    });
  }

  // The joints' own forces Q by dual numbers: their values kept for b, their
  // derivatives for below. They read nothing the passes make and come
  // before them, where the processor can work on them while the pass down
  // the tree waits on the links' poses. Computed after the pass up the
  // tree instead, the spatial arm's Jacobian (three drives that read the
  // state) took 510 against 487 ns (tools/probes/small_jacobians.cpp, nine
  // runs in turns) and 501 against 475 ns (build/benchmarks/jacobian, ten
  // runs in turns; its URDF twin 492 against 497 ns, within the noise).
  // A force of the joint's own q, v and the time
  // (an axis law, a drive of t) in those three directions; a drive that reads
  // the state (τ(t, x)) in every direction of the state and the time, its
  // row of ∂Q/∂x dense. (A ball transmits nothing of its own.)
  std::array<std::array<double, 3>, NN> dQ{};
  std::array<double, NN> Qv;  // Q, by node: into b once the pass up the tree has formed it
  using reading = state_reading_links<S>;
  using DW = dual<double, 2 * N + 1>;
  constexpr auto loads = load_flags<S>::value;
  constexpr bool loaded = has_link_loads<S>(), local = loaded && local_loads<S>();
  // The state and the time in every direction, for the drives that read the
  // state and the force elements that do not take local lanes: q's
  // directions by rate, a ball's quaternion moving by ½·Q ⊗ (e_k, 0) in its
  // rotation rate k's.
  constexpr bool wide = reading::count > 0 || (loaded && !local);
  std::array<DW, wide ? S::n_q : 0> qw;
  std::array<DW, wide ? N : 0> vw;
  if constexpr (wide) {
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      if constexpr (ball_links<S>[L]) {
        constexpr int qa = LI::joint_type::quaternion_at;
        for (int k = 0; k < qa; ++k) qw[LI::q + k] = DW::variable(q[LI::q + k], LI::v + k);
        const double* Q = q + LI::q + qa;
        double dQc[3][4];
        for (int c = 0; c < 3; ++c) {
          const double e[3] = {double(c == 0), double(c == 1), double(c == 2)};
          quaternion::rate(Q, e, dQc[c]);
        }
        for (int k = 0; k < 4; ++k)
          qw[LI::q + qa + k] = DW::with_lanes(Q[k], [&](int l) {
            const int c = l - (LI::v + qa);
            return c >= 0 && c < 3 ? dQc[c][k] : 0.0;
          });
      } else {
        for (int k = 0; k < LI::joint_type::nq; ++k) qw[LI::q + k] = DW::variable(q[LI::q + k], LI::v + k);
      }
    });
    for (int k = 0; k < N; ++k) vw[k] = DW::variable(v[k], N + k);
  }
  std::array<DW, reading::count> dQ_read;
  if constexpr (has_joint_forces<S>()) {
    using D = dual<double, 3>;
    std::array<D, S::n_q> qx;
    std::array<D, N> vx;
    for (int k = 0; k < S::n_q; ++k) qx[k] = D(q[k]);
    for (int k = 0; k < N; ++k) vx[k] = D(v[k]);
    const auto x = state_view(scene, qx.data(), vx.data());
    const D td = D::variable(t, 2);
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value, n = nodes::table.last[L];
      using LI = link_info<S, L>;
      using J = typename LI::joint_type;
      if constexpr (force_reads_state<J>()) {
        constexpr int k = reading::index_of(L);
        const auto xw = state_view(scene, qw.data(), vw.data());
        DW& tau = dQ_read[k];
        scene.template component<LI::joint>().generalized_force(DW::variable(t, 2 * N), xw, qw.data() + LI::q,
                                                                 vw.data() + LI::v, &tau);
        Qv[n] = tau.v;
      } else if constexpr (has_generalized_force<J>) {
        qx[LI::q] = D::variable(q[LI::q], 0);
        vx[LI::v] = D::variable(v[LI::v], 1);
        D tau;
        scene.template component<LI::joint>().generalized_force(td, x, qx.data() + LI::q, vx.data() + LI::v, &tau);
        Qv[n] = tau.v;
        dQ[n] = {tau.d[0], tau.d[1], tau.d[2]};
        qx[LI::q] = D(q[LI::q]);
        vx[LI::v] = D(v[LI::v]);
      }
    });
  }

  // Down the tree: poses, the columns and velocities in the passes' frame, and the
  // accelerations as they would be at v̇ = 0 (acc⁰; the true ones follow once
  // v̇ is known, below); each body's inertia, its wrench at acc⁰ and its
  // velocity coupling, at its link's last node (the others carry none).
  // Composites, couplings and wrenches live at each link's last node (top:
  // the header's "A link's nodes but its last").
  std::array<spatial<G>, NN> s, vel, acc, u, psi, F;
  std::array<world_inertia<G>, NN> Ic;
  std::array<velocity_coupling<G>, NN> Bc;
  static constexpr auto top_table = [] {
    std::array<int, NN> t{};
    for (int n = 1; n < NN; ++n) t[n] = nodes::table.last[nodes::table.link[n]];
    return t;
  }();
  auto top = [](int n) FLANGE_INLINE_LAMBDA { return one_node_links ? n : top_table[n]; };
  // The passes hold in any fixed frame. Theirs has its origin at link 1's
  // origin, not the World's: a base far from the World's origin would
  // otherwise carry its lever arm (m·|r|²) into every inertia, where a light
  // link's few 1e-4 kg m² are lost to round-off. Its axes are link 1's at q
  // (R[L], r[L]: link L's pose in it; R[0], r[0]: the World's), so that
  // link 1's columns and inertia are its own, with no turn (a chain of one
  // link: 1,190 → 829 instructions, of two 3,430 → 3,194); but the World's
  // where the loads of force elements on links come from dual numbers in the
  // links' motions (local_loads: local_lanes, below, are in world
  // coordinates).
  constexpr bool link1_axes = !(has_link_loads<S>() && local_loads<S>());
  if constexpr (link1_axes) {
    R[0] = E[1];
    r[0] = -rotate(E[1], p[1]);
    R[1].setIdentity();
    r[1].setZero();
  } else {
    R[0].setIdentity();
    r[0].setZero();
  }
  for (int L = link1_axes ? 2 : 1; L < NL; ++L) {
    const int P = link_parent[L];
    R[L] = rotate_nt(R[P], E[L]);
    r[L] = plus(r[P], rotate(R[P], p[L]));
  }
  // The nodes' columns by shape in the passes' frame (column_dot and the
  // products beside it), where every link hangs from link 1: in link 1's
  // axes its rates' columns are, by type, translations (a Prismatic at the
  // root, a floating base's) and turns about coordinate axes through the
  // origin (a Revolute at the root, whose link's axes put its axis on one
  // of theirs, a ball's rotation rates), and its nodes 1 … trunk are every
  // node's last ancestors. Without a ball at link 1, only on a tree whose
  // passes are written out node by node (over_nodes: up to
  // written_out_nodes), where its first node's products are then its
  // shape's alone (the spatial arm's Jacobian: 5,239 → 4,513 instructions,
  // tools/jacobian_counts.sh); on longer chains the trunk written out
  // apart from the loop over the other nodes ran as fast or slower (a
  // 32-link chain 40 % slower for 2 % more instructions). Elsewhere every
  // column is any_column.
  constexpr int trunk = nodes::table.last[1];
  // A trunk node's shape by type. A turn has one only where its velocity
  // parent moves by translation alone (the World, or a floating base's
  // translations): its u and ψ then have no angular part, which the passes
  // below also use.
  static constexpr auto shape_by_type = [] {
    std::array<int, NN> k{};
    for (int n = 0; n < NN; ++n)
      k[n] = n == 0 || n > trunk ? any_column
             : parts.no_ang[n]   ? translation_column
             : parts.no_lin[n] && parts.axis[n] >= 0 && translating_nodes<S>[nodes::table.vparent[n]]
                 ? parts.axis[n]
                 : any_column;
    return k;
  }();
  constexpr bool trunk_shapes = [] {
    for (int n = 1; n <= trunk; ++n)
      if (shape_by_type[n] != any_column) return true;
    return false;
  }();
  constexpr bool shaped = !in_plane && link1_axes &&
                          (ball_links<S>[1] || (trunk_shapes && NN - 1 <= written_out_nodes)) && [] {
    for (int L = 2; L < NL; ++L) {
      int P = S::tree.link_parent[L];
      while (P > 1) P = S::tree.link_parent[P];
      if (P != 1) return false;
    }
    return true;
  }();
  // The shapes the passes take: the trunk's where columns are shaped.
  static constexpr auto shape = [] {
    std::array<int, NN> k{};
    for (int n = 0; n < NN; ++n) k[n] = shaped ? shape_by_type[n] : any_column;
    return k;
  }();
  // f(j, k) for node `from` and each of its ancestors, nearest first, k the
  // shape of j's column (a constant): where columns are shaped, the trunk's
  // nodes written out, each with j a constant; from a trunk node given as a
  // constant (children_first, below), its ancestors alone.
  auto up_from = [&](auto from, auto&& f) FLANGE_INLINE_LAMBDA {
    if constexpr (requires { decltype(from)::value; }) {
      static_for<trunk>([&](auto t) FLANGE_INLINE_LAMBDA {
        constexpr int jt = trunk - decltype(t)::value;
        if constexpr (jt <= decltype(from)::value) f(jt, std::integral_constant<int, shape[jt]>{});
      });
    } else if constexpr (shaped) {
      int j = from;
      if constexpr (trunk < NN - 1)  // nodes below the trunk
        for (; j > trunk; j = parent[j]) f(j, std::integral_constant<int, any_column>{});
      static_for<trunk>([&](auto t) FLANGE_INLINE_LAMBDA {
        constexpr int jt = trunk - decltype(t)::value;
        if (jt <= j) f(jt, std::integral_constant<int, shape[jt]>{});
      });
    } else {
      for (int j = from; j != 0; j = parent[j]) f(j, std::integral_constant<int, any_column>{});
    }
  };
  // step(n, k) for every node n, parents first or children first, k the
  // shape of its column (a constant): where columns are shaped, the trunk's
  // nodes written out, each n a constant (an integral_constant), so that its
  // products with its column are its shape's alone, with no test at run
  // time.
  auto parents_first = [&](auto&& step) FLANGE_INLINE_LAMBDA {
    if constexpr (shaped) {
      static_for<trunk>([&](auto t) FLANGE_INLINE_LAMBDA {
        constexpr int n = 1 + decltype(t)::value;
        step(std::integral_constant<int, n>{}, std::integral_constant<int, shape[n]>{});
      });
      for (int n = trunk + 1; n < NN; ++n) step(n, std::integral_constant<int, any_column>{});
    } else {
      over_nodes<NN, false, in_plane>(
          [&](const int n) FLANGE_INLINE_LAMBDA { step(n, std::integral_constant<int, any_column>{}); });
    }
  };
  auto children_first = [&](auto&& step) FLANGE_INLINE_LAMBDA {
    if constexpr (shaped) {
      // The nodes below the trunk as over_nodes takes them.
      if constexpr (NN - 1 <= written_out_nodes)
        static_for<NN - 1 - trunk>([&](auto k) FLANGE_INLINE_LAMBDA {
          step(NN - 1 - int(k), std::integral_constant<int, any_column>{});
        });
      else
        for (int n = NN - 1; n > trunk; --n) step(n, std::integral_constant<int, any_column>{});
      static_for<trunk>([&](auto t) FLANGE_INLINE_LAMBDA {
        constexpr int n = trunk - decltype(t)::value;
        step(std::integral_constant<int, n>{}, std::integral_constant<int, shape[n]>{});
      });
    } else {
      over_nodes<NN, true>([&](const int n) FLANGE_INLINE_LAMBDA { step(n, std::integral_constant<int, any_column>{}); });
    }
  };
  // Node n's parent, a constant where n is.
  auto parent_of = [](auto n) FLANGE_INLINE_LAMBDA {
    if constexpr (requires { decltype(n)::value; }) return std::integral_constant<int, nodes::table.parent[decltype(n)::value]>{};
    else return nodes::table.parent[n];
  };
  const typename G::lin r1 = r[1];
  if constexpr (!link1_axes)
    for (int L = 1; L < NL; ++L) r[L] -= r1;
  const spatial<G> zero{G::zero_ang(), G::lin::Zero()};
  vel[0] = acc[0] = zero;
  if constexpr (S::has_gravity) {
    if constexpr (link1_axes) acc[0].l = rotate(R[0], G::lin_of(scene.model().minus_g));
    else acc[0].l = G::lin_of(scene.model().minus_g);
  }
  parents_first([&](const auto n, auto kn) FLANGE_INLINE_LAMBDA {
    const int L = node_link[n], P = parent[n], V = vparent[n];
    // A column's part that is zero by type stays zero: no turn of it; nor
    // of link 1's columns in its own axes.
    if (link1_axes && L == 1) s[n] = col[n];
    else if (parts.no_ang[n]) s[n] = {G::zero_ang(), rotate(R[L], col[n].l)};
    else if (parts.no_lin[n]) s[n] = {turn(R[L], col[n].a), cross(r[L], turn(R[L], col[n].a))};
    else s[n] = {turn(R[L], col[n].a), plus(rotate(R[L], col[n].l), cross(r[L], turn(R[L], col[n].a)))};
    const double qd = v[rate[n]];
    vel[n] = plus_column<G>(kn, vel[P], s[n], qd);
    if (!translating[V]) {
      u[n] = column_motion_cross<G>(kn, s[n], vel[V]);
    } else if (translating[n]) {
      u[n] = zero;
    } else {
      u[n] = column_angular_cross<G>(kn, s[n], vel[V].l);
    }
    acc[n] = translating[n] ? acc[P] : acc[P] - u[n] * qd;  // v_L × s_L = v_V × s_L
    if (one_node_links || n == last[L]) {
      Ic[n] = link1_axes && L == 1 ? G::at_link(scene.model().link[1])
                                   : G::to_world(scene.model().link[L], R[L], r[L]);
      const spatial<G> h = Ic[n] * vel[n];
      F[n] = Ic[n] * acc[n] + force_cross(vel[n], h);
      Bc[n] = G::coupling_of(Ic[n], vel[n], h);
    } else if constexpr (Articulated) {  // the factor's own inertias (below)
      Ic[n] = {0, G::lin::Zero(), G::zero_moment()};
      F[n] = {G::zero_ang(), G::lin::Zero()};
      Bc[n] = {G::zero_moment(), G::lin::Zero()};
    }
  });
  // What ∂/∂v reads for u: a ball's rotation columns turn with its link
  // while the next ones' u read the velocity before the ball, which adds
  // ½·s × (v_L − v_V) to it; a node of one rate's is u.
  std::conditional_t<balls, std::array<spatial<G>, NN>, std::array<int, 0>> uv_ball;
  if constexpr (balls)
    parents_first([&](const auto n, auto kn) FLANGE_INLINE_LAMBDA {
      uv_ball[n] = u[n];
      if (nodes::table.ball[n])
        uv_ball[n] += column_motion_cross<G>(kn, s[n], vel[last[node_link[n]]] - vel[vparent[n]]) * 0.5;
    });
  auto uv = [&](int n) -> const spatial<G>& {
    if constexpr (balls) return uv_ball[n];
    else return u[n];
  };

  // Up the tree: the composites, M, the forces τ⁰ at v̇ = 0 and what does not
  // depend on v̇ (∂/∂v) for each pair of node n and an ancestor (M and the
  // derivatives are zero between nodes on different branches). Rows in node
  // order (parents first), so that M's factor keeps the tree's zeros; columns
  // in rate order.
  // M (of the articulated-body factor's chain, nothing: it needs no entry
  // of M) and each node's pivot yardstick: the inertia its composite has
  // about the passes' fixed point (the trace of its rotational inertia plus
  // its mass), which the round-off of M(n, n) and of its pivot scale with.
  // (Not M(n, n) itself: that is round-off where the joint moves nothing
  // with inertia, a point mass on its axis.)
  std::conditional_t<Articulated, std::array<int, 0>, Eigen::Matrix<double, N, N>> M;
  std::array<double, N> yard;
  Eigen::Matrix<double, N, 1> b;  // Q − τ⁰, then v̇, by node
  std::array<spatial<G>, NN> y;   // I_n·s_n
  std::array<typename G::ang, NN> z;  // the angular part of B_nᵀ·s_n
  constexpr bool chain = nodes::chain;
  static_assert(chain || !Articulated, "the articulated-body factor is a chain's");
  if constexpr (!chain) {
    out.setZero();
  } else if constexpr (constexpr int padding = tree_solve_row(2 * N + 1) - (2 * N + 1); padding > 0) {
    out.template rightCols<padding>().setZero();
  }
  // On a chain of seven nodes or more without balls or loads on its links,
  // whose rates follow its nodes (rate[n] = n − 1), node n's ancestors are
  // nodes 1 … n and their pairs' columns 0 … n − 1: each pair's products are
  // then sums over the numbers of the columns s_j (and u_j, ψ_j) stacked a
  // number at a time, loops over j that the compiler vectorizes (sc[c][j]:
  // number c of s_j). On shorter chains the stacks cost more than they save
  // (docs/performance.md, "The Jacobian").
  constexpr bool stacked = chain && !balls && !has_link_loads<S>() && N >= 7 && [] {
    for (int n = 1; n < NN; ++n)
      if (nodes::table.rate[n] != n - 1) return false;
    return true;
  }();
  constexpr bool in_space = !in_plane;
  constexpr int C = in_space ? 6 : 3, CA = in_space ? 3 : 1;  // numbers, angular ones
  using stack = std::conditional_t<stacked, std::array<std::array<double, NN>, C>, std::array<int, 0>>;
  alignas(32) stack sc, uc, pc;  // s, u (which ∂/∂v reads without balls) and, below, ψ
  if constexpr (stacked)
    for (int n = 1; n < NN; ++n) {
      const auto sn = numbers(s[n]), un = numbers(u[n]);
      for (int c = 0; c < C; ++c) {
        sc[c][n] = sn[c];
        uc[c][n] = un[c];
      }
    }
  // M's factor on a long chain (Articulated): its articulated-body factor
  // (math/chain_solve.hpp), from the columns and the bodies' own inertias
  // (the pass below sums them into the composites), no entry of M formed.
  // The pass carries it a node at a time: alone, the factor runs at the
  // latency of its chain of divisions, which the pass's own products hide.
  constexpr double tol = pivot_tolerance<N, double>();
  std::conditional_t<Articulated, std::array<world_inertia<G>, NN>, std::array<int, 0>> own;
  std::conditional_t<Articulated, chain_factor<N, C>, std::array<int, 0>> chain_M;
  if constexpr (Articulated) {
    own = Ic;
    chain_M.start();
  }
  children_first([&](const auto n, auto kn) FLANGE_INLINE_LAMBDA {
    const int i = rate[n], t = top(n);
    y[n] = inertia_times_column<G>(kn, Ic[t], s[n]);
    z[n] = coupling_transposed_times_column<G>(kn, Bc[t], s[n]);
    b[n - 1] = -column_dot<G>(kn, s[n], F[t]);
    // (A node that moves by translation alone has u = 0.)
    const spatial<G> Gv = translating[n] ? coupling_times_column<G>(kn, Bc[t], s[n])
                                         : coupling_times_column<G>(kn, Bc[t], s[n]) + Ic[t] * uv(n) * 2;
    yard[n - 1] = trace_of(Ic[t].I) + Ic[t].m;
    if constexpr (stacked) {
      const auto yn = numbers(y[n]), zn = numbers(spatial<G>{z[n], G::lin::Zero()}), gv = numbers(Gv);
      for (int j = 1; j <= n; ++j) {
        double m = 0, e = 0;
        for (int c = 0; c < C; ++c) {
          if constexpr (!Articulated) m += yn[c] * sc[c][j];
          e += 2 * yn[c] * uc[c][j];
        }
        for (int c = 0; c < CA; ++c) e += zn[c] * sc[c][j];
        if constexpr (!Articulated) M(n - 1, j - 1) = m;
        out(n - 1, N + j - 1) = e;
      }
      for (int j = 1; j < n; ++j) {
        double e = 0;
        for (int c = 0; c < C; ++c) e += gv[c] * sc[c][j];
        out(j - 1, N + i) = e;
      }
    } else {
      up_from(n, [&](int j, auto kj) FLANGE_INLINE_LAMBDA {
        if constexpr (!Articulated) M(n - 1, j - 1) = column_dot<G>(kj, s[j], y[n]);
        out(n - 1, N + rate[j]) = translating[j] ? 0.0 : column_angular_dot<G>(kj, z[n], s[j]) + 2 * y[n].dot(uv(j));
      });
      up_from(parent_of(n), [&](int j, auto kj) FLANGE_INLINE_LAMBDA { out(j - 1, N + i) = column_dot<G>(kj, s[j], Gv); });
    }
    if constexpr (Articulated) chain_M.node(n - 1, numbers(s[n]), G::matrix_of(own[n]), yard[n - 1], tol);
    if (const int P = parent[n]; P != 0 && (one_node_links || top(P) != t)) {  // n: its link's first node
      Ic[top(P)] += Ic[t];
      Bc[top(P)] += Bc[t];
      F[top(P)] += F[t];
    }
  });
  // Q joins b: b = −s·F + Q, and the loads' s·W below.
  if constexpr (has_joint_forces<S>())
    for_links<S>([&](auto l) {
      constexpr int L = decltype(l)::value;
      using J = typename link_info<S, L>::joint_type;
      if constexpr (force_reads_state<J>() || has_generalized_force<J>) b[last[L] - 1] += Qv[last[L]];
    });

  // The force elements' loads on each link, as wrenches W_L at the passes'
  // fixed point: they enter τ_i as −s_iᵀ·Σ_{L in i's subtree} W_L, into b
  // here; their derivatives after the passes, below. Force elements are
  // written once, generic in their scalar, and differentiated by dual
  // numbers: where none reads the joint state (local_loads), each element in
  // the motions of the links it sits on (local_lanes: 12 directions a link
  // and the time), carried to the state's directions through the columns
  // (moving q_j of an ancestor of link P moves P by s_j and changes its
  // twist v_P by s_j × v_P − u_j; moving v_j changes it by s_j), into dL;
  // else all of them in every direction of the state (n about the link's
  // origin and f, link coordinates).
  std::conditional_t<loaded && !local, link_loads<S, DW>, std::array<int, 0>> n_w, f_w;
  std::array<spatial<G>, NN> W_own, W;  // each link's, at its last node; summed over the node's subtree
  using load_rows = Eigen::Matrix<double, N, 2 * N + 1, Eigen::RowMajor>;
  std::conditional_t<local, load_rows, std::array<int, 0>> dL;
  if constexpr (loaded) {
    for (int n = 0; n < NN; ++n) W_own[n] = {G::zero_ang(), G::lin::Zero()};
    if constexpr (local) {
      dL.setZero();
      auto element = [&]<int C>(std::integral_constant<int, C>) {
        using Comp = typename S::template component_type<C>;
        if constexpr (Comp::kind == role::force) {
          if constexpr (force_acts<S, C>()) {
            using EL = element_links<S, C>;
            constexpr int m = EL::count, lanes = 12 * m + 1, nf = int(Comp::frames.size());
            constexpr auto links = EL::frame_links;
            using D = dual<double, lanes>;
            std::array<link_pose<D, velocity_in::link>, m> lp;
            static_for<m>([&](auto k) {
              constexpr int L = EL::link[k];
              lp[k] = local_lanes<D, 12 * int(k)>(R[L], r[L], r1, vel[last[L]]);
            });
            // Adds f and n (a wrench at the fixed point, world coordinates)
            // on link l: its value to l's own, its derivatives carried to
            // the state's directions.
            auto add = [&](int l, const Vec3<D>& f, const Vec3<D>& n) {
              const int nl = last[l];
              W_own[nl] += spatial<G>{lane(n, -1), lane(f, -1)};
              auto project = [&](int c, const spatial<G>& dW) {
                for (int i = nl; i != 0; i = parent[i]) dL(i - 1, c) += s[i].dot(dW);
              };
              project(2 * N, {lane(n, lanes - 1), lane(f, lanes - 1)});
              for (int b = 0; b < m; ++b) {
                const int P = EL::link[b], np = last[P];
                std::array<spatial<G>, 12> g;  // ∂W in P's 12 directions
                for (int c = 0; c < 12; ++c) g[c] = {lane(n, 12 * b + c), lane(f, 12 * b + c)};
                for (int j = np; j != 0; j = parent[j]) {
                  const spatial<G> tw = motion_cross(s[j], vel[np]) - u[j];
                  spatial<G> dq{G::zero_ang(), G::lin::Zero()}, dv = dq;
                  for (int c = 0; c < 3; ++c) {
                    dq += g[c] * s[j].a[c] + g[3 + c] * s[j].l[c] + g[6 + c] * tw.a[c] + g[9 + c] * tw.l[c];
                    dv += g[6 + c] * s[j].a[c] + g[9 + c] * s[j].l[c];
                  }
                  project(rate[j], dq);
                  project(N + rate[j], dv);
                }
              }
            };
            if constexpr (meets_resting_half_space<S, C>()) {
              // A contact with a half-space at rest in the World: the code
              // the derivative runs for it (resting_half_space_loads, its
              // loads in link coordinates about the link's origin) in its
              // link's 12 lanes, turned into the world at the fixed point.
              const link_pose<D, velocity_in::link>& P = lp[0];
              Vec3<D> fL = Vec3<D>::Zero(), nL = Vec3<D>::Zero();
              resting_half_space_loads<S, C>(scene, P, fL, nL);
              const Vec3<D> f = P.R.transpose() * fL;
              add(EL::link[0], f, P.R.transpose() * nL + (P.r - r1.template cast<D>()).cross(f));
            } else {
              std::array<frame_kinematics<D>, nf> fk;
              static_for<nf>([&](auto k) {
                constexpr int K = decltype(k)::value;
                fk[K] = frame_from_link<S, C, K>(scene, lp[EL::block_of(links[K])]);
              });
              // (It reads no state; the state is there for its signature.)
              std::array<D, S::n_q> ql;
              std::array<D, N> vl;
              for (int i = 0; i < S::n_q; ++i) ql[i] = D(q[i]);
              for (int i = 0; i < N; ++i) vl[i] = D(v[i]);
              std::array<wrench<D>, nf> on;
              scene.template component<C>().wrenches(D::variable(t, lanes - 1),
                                                     state_view(scene, ql.data(), vl.data()), fk.data(), on.data());
              for (int k = 0; k < nf; ++k) {
                const int l = links[k];
                if (l == 0) continue;
                // What it exerts at frame k, as a wrench at the fixed point.
                Vec3<D> f = Vec3<D>::Zero(), n = Vec3<D>::Zero();
                if constexpr (Comp::exerts_force) {
                  f = on[k].f;
                  n = (fk[k].r - r1.template cast<D>()).cross(f);
                }
                if constexpr (Comp::exerts_torque) n += on[k].n;
                add(l, f, n);
              }
            }
          }
        }
      };
      [&]<int... C>(std::integer_sequence<int, C...>) {
        (element(std::integral_constant<int, C>{}), ...);
      }(std::make_integer_sequence<int, S::n_components>{});
    } else {
      const auto xw = state_view(scene, qw.data(), vw.data());
      const auto mw = link_motions<spatial_algebra, DW, true>(scene, qw.data());
      gather_external<spatial_algebra>(scene, DW::variable(t, 2 * N), xw, mw, mw, n_w, f_w);
      for (int L = 1; L < NL; ++L)
        if (loads.torque[L]) {
          W_own[last[L]] =
              world_wrench<G>(R[L], r[L], lane(n_w[L], -1), loads.force[L] ? lane(f_w[L], -1) : Vec3d::Zero());
        }
    }
    W = W_own;
    for (int n = NN - 1; n >= 1; --n) {
      b[n - 1] += s[n].dot(W[n]);
      if (const int P = parent[n]; P != 0) W[P] += W[n];
    }
  }

  // M's factor: on a long chain (Articulated) the articulated-body factor
  // the pass up the tree carried; else M = Lᵀ·D·L (Featherstone's LTDL
  // factorization, leaves first: L has the tree's zeros, where a root-first
  // factor would join siblings), in M as math/tree_solve.hpp reads it: U =
  // D·L below the diagonal (what the elimination leaves there), L above it.
  // Either way a pivot at or below pivot_tolerance of its yardstick stops it
  // (a joint that moves nothing with inertia, or whose motion repeats
  // others').
  std::array<double, NN> inv;  // 1 / D_k
  if constexpr (Articulated) {
    if (chain_M.failed >= 0) [[unlikely]]
      return {rate[chain_M.failed + 1], chain_M.failed_d, yard[chain_M.failed]};
    chain_M.finish();
  } else if constexpr (chain && !unrolled_factor<S>()) {
    // Every node above k: dense loops the compiler vectorizes.
    std::array<double, N> c;
    for (int k = N - 1; k >= 0; --k) {
      if (!(M(k, k) > tol * yard[k])) [[unlikely]]
        return {rate[k + 1], M(k, k), yard[k]};
      const double e = inv[k + 1] = 1 / M(k, k);
      for (int i = 0; i < k; ++i) c[i] = M(i, k) = M(k, i) * e;
      for (int j = 0; j < k; ++j)
        for (int i = j; i < k; ++i) M(i, j) -= c[i] * M(k, j);
    }
  } else if constexpr (unrolled_factor<S>()) {
    if (const int k = factor_tree_written_out<S>(M, yard, tol, inv); k != 0) [[unlikely]]
      return {rate[k], M(k - 1, k - 1), yard[k - 1]};
  } else {
    for (int k = NN - 1; k >= 1; --k) {
      if (!(M(k - 1, k - 1) > tol * yard[k - 1])) [[unlikely]]
        return {rate[k], M(k - 1, k - 1), yard[k - 1]};
      const double e = inv[k] = 1 / M(k - 1, k - 1);
      // k's ancestors, nearest first (factor_ancestry), and row k's entries
      // for them: each pair's update reads two lists, no walk up the tree.
      using anc = factor_ancestry<S>;
      const auto& up = anc::up[k];
      const int depth = anc::depth[k];
      std::array<double, NN> c, w;  // rows k of L and of U
      for (int a = 0; a < depth; ++a) c[a] = M(up[a], k - 1) = (w[a] = M(k - 1, up[a])) * e;
      for (int a = 0; a < depth; ++a) {
        double* row = &M(up[a], 0);
        const double ca = c[a];
        for (int b = a; b < depth; ++b) row[up[b] * N] -= ca * w[b];
      }
    }
  }
  // The solves: the articulated-body factor's two sweeps
  // (math/chain_solve.hpp), or both triangular solves of the LTDL
  // factor with the tree's zeros (math/tree_solve.hpp, tree giving each
  // node's descendants and ancestors).
  using tree = node_runs<S>;
  // v̇ = M⁻¹·(Q − τ⁰); then each node's acceleration changes by δa_n = δa_P +
  // s_n·v̇_n, and ψ_n = s_n × a_V − u_n × v_V follows (V: vparent).
  if (force)
    for (int n = 1; n < NN; ++n) b[n - 1] += force[rate[n]];
  if constexpr (Articulated) {
    chain_solve_column(chain_M, b.data());
  } else {
    tree_solve_block<tree, 1>(M.data(), N, inv.data(), b.data(), 1, 0);
  }
  if (vdot)
    for (int n = 1; n < NN; ++n) vdot[rate[n]] = b[n - 1];
  std::array<spatial<G>, NN> da;
  da[0] = {G::zero_ang(), G::lin::Zero()};
  parents_first([&](const auto n, auto kn) FLANGE_INLINE_LAMBDA {
    const int P = parent[n], V = vparent[n];
    da[n] = plus_column<G>(kn, da[P], s[n], b[n - 1]);
    if (!translating[V]) {
      psi[n] = column_motion_cross<G>(kn, s[n], acc[V] + da[V]) - motion_cross(u[n], vel[V]);
    } else if (translating[n]) {
      psi[n] = zero;
    } else {
      psi[n] = column_angular_cross<G>(kn, s[n], plus(acc[V].l, da[V].l));
    }
    if constexpr (stacked) {
      const auto pn = numbers(psi[n]);
      for (int c = 0; c < C; ++c) pc[c][n] = pn[c];
    }
  });
  // Up the tree again: the subtree's wrench at v̇, F_n = F⁰_n + I_n·δa_n + Y_n
  // with Y_n = Σ over n's children c of (I_c·s_c·v̇_c + Y_c), and the pairs'
  // ∂/∂q; then the joints' own.
  std::array<spatial<G>, NN> Y;
  for (int n = 0; n < NN; ++n) Y[n] = {G::zero_ang(), G::lin::Zero()};
  children_first([&](const auto n, auto kn) FLANGE_INLINE_LAMBDA {
    const int i = rate[n], t = top(n);
    if (t == n) F[n] += Ic[n] * da[n] + Y[n];  // else its link's last node's, done
    // With loads, ∂s_n/∂q_j = s_j × s_n turns their share: −(s_j × s_n)ᵀ·W_n.
    std::conditional_t<loaded, spatial<G>, int> gw{};
    if constexpr (loaded) gw = force_cross(s[n], W[n]);
    // A shaped turn's u and ψ have no angular part (its velocity parent
    // moves by translation alone), so that B·u is zero and I·ψ reads ψ's
    // linear part.
    spatial<G> Gq = column_force_cross<G>(kn, s[n], F[t]);
    if (kn >= 0) Gq = Gq - inertia_times_column<G>(translation_column, Ic[t], psi[n]);
    else if (!translating[n]) Gq = Gq + Bc[t] * u[n] - Ic[t] * psi[n];
    if constexpr (stacked) {
      const auto yn = numbers(y[n]), zn = numbers(spatial<G>{z[n], G::lin::Zero()}), gq = numbers(Gq);
      for (int j = 1; j <= n; ++j) {
        double e = 0;
        for (int c = 0; c < C; ++c) e += yn[c] * pc[c][j];
        for (int c = 0; c < CA; ++c) e -= zn[c] * uc[c][j];
        out(n - 1, j - 1) = e;
      }
      for (int j = 1; j < n; ++j) {
        double e = 0;
        for (int c = 0; c < C; ++c) e -= gq[c] * sc[c][j];
        out(j - 1, i) = e;
      }
    } else {
      up_from(n, [&](int j, auto kj) FLANGE_INLINE_LAMBDA {
        double e = translating[j] ? 0.0
                   : kj >= 0      ? column_dot<G>(translation_column, psi[j], y[n])
                                  : y[n].dot(psi[j]) - inner(z[n], u[j].a);
        if constexpr (loaded) e += column_dot<G>(kj, s[j], gw);
        out(n - 1, rate[j]) = e;
      });
      up_from(parent_of(n), [&](int j, auto kj) FLANGE_INLINE_LAMBDA {
        // Within a ball, node j's column turns with n's rate too: row j,
        // column n as for an ancestor.
        if (balls && nodes::table.group[j] == nodes::table.group[n]) {
          double e = y[j].dot(psi[n]) - inner(z[j], u[n].a);
          if constexpr (loaded) e += s[n].dot(force_cross(s[j], W[j]));
          out(j - 1, i) = e;
        } else {
          out(j - 1, i) = -column_dot<G>(kj, s[j], Gq);
        }
      });
    }
    Y[parent[n]] += y[n] * b[n - 1] + Y[n];
    out(n - 1, i) += dQ[n][0];
    out(n - 1, N + i) += dQ[n][1];
    out(n - 1, 2 * N) = dQ[n][2];
  });
  for (int k = 0; k < reading::count; ++k)
    for (int c = 0; c <= 2 * N; ++c) out(last[reading::link[k]] - 1, c) += dQ_read[k].d[c];
  if constexpr (local) out.template leftCols<2 * N + 1>() += dL;
  if constexpr (loaded && !local) {
    // ∂W_L/∂x: the loads' own derivatives turned into the world, and for q_j
    // of L's ancestors (and L) the turn of W_L itself, s_j ×* W_L; each
    // projected on the columns of L and its ancestors.
    for (int L = 1; L < NL; ++L) {
      if (!loads.torque[L]) continue;
      const int n = last[L];
      for (int c = 0; c <= 2 * N; ++c) {
        const spatial<G> dW =
            world_wrench<G>(R[L], r[L], lane(n_w[L], c), loads.force[L] ? lane(f_w[L], c) : Vec3d::Zero());
        for (int i = n; i != 0; i = parent[i]) out(i - 1, c) += s[i].dot(dW);
      }
      for (int j = n; j != 0; j = parent[j]) {
        const spatial<G> turned = force_cross(s[j], W_own[n]);
        for (int i = n; i != 0; i = parent[i]) out(i - 1, rate[j]) += s[i].dot(turned);
      }
    }
  }
  // M⁻¹ on the columns: ∂/∂t's only where some of it is not zero (a drive
  // or a load that changes with the time), and where leaving it out spares
  // four of the solve's columns (2N a multiple of four); a zero column
  // stays zero.
  constexpr int row = tree_solve_row(2 * N + 1);
  auto solve = [&](auto cols) FLANGE_INLINE_LAMBDA {
    constexpr int Cols = decltype(cols)::value;
    if constexpr (Articulated) chain_solve<N, C, Cols, row>(chain_M, out.data());
    else tree_solve<tree, Cols, row>(M.data(), N, inv.data(), out.data());
  };
  if constexpr (tree_solve_row(2 * N) < row) {
    bool steady = true;
    for (int n = 0; n < N; ++n) steady = steady && out(n, 2 * N) == 0;
    if (steady) {
      solve(std::integral_constant<int, 2 * N>{});
      return {};
    }
  }
  solve(std::integral_constant<int, 2 * N + 1>{});
  return {};
}

/// The passes as every x86-64 runs them (SSE2, or what the build's -march
/// gives).
template <class S, bool Articulated>
pivot_report<double> acceleration_derivatives_portable(const S& scene, double t, const double* q, const double* v,
                                                       derivative_rows<S>& out, double* vdot,
                                                       const double* force = nullptr) {
  return acceleration_derivatives_passes<S, Articulated>(scene, t, q, v, out, vdot, force);
}

#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
/// The same passes compiled for AVX2: three-operand instructions (no copy
/// of a register before each product) and four numbers a register where the
/// compiler vectorizes (the stacked pairs). Without fused multiply-adds
/// (no "fma" target): each product and sum is rounded as in the portable
/// passes, so that both give the same numbers to the bit, in any build.
/// (Where the compiler is free to fuse, it fuses where its inlining lets it,
/// which differs from one build to the next: the Python module's Jacobians
/// would differ from the C++ API's in their last bits.)
template <class S, bool Articulated>
[[gnu::target("avx2")]] pivot_report<double> acceleration_derivatives_avx2(const S& scene, double t, const double* q,
                                                                           const double* v, derivative_rows<S>& out,
                                                                           double* vdot, const double* force = nullptr) {
  return acceleration_derivatives_passes<S, Articulated>(scene, t, q, v, out, vdot, force);
}
#endif

/// ∂v̇/∂x by the passes above (acceleration_derivatives_passes), compiled for
/// AVX2 where the processor runs it (detail/cpu.hpp, asked once) and
/// FLANGE_NO_AVX2 is not defined, else for every x86-64: the same numbers
/// either way.
template <class S, bool Articulated = articulated_solve<S>()>
pivot_report<double> acceleration_derivatives(const S& scene, double t, const double* q, const double* v,
                                              derivative_rows<S>& out, double* vdot = nullptr,
                                              const double* force = nullptr) {
#if defined(FLANGE_X86_DISPATCH) && !defined(FLANGE_NO_AVX2)
  if (cpu_has_avx2) return acceleration_derivatives_avx2<S, Articulated>(scene, t, q, v, out, vdot, force);
#endif
  return acceleration_derivatives_portable<S, Articulated>(scene, t, q, v, out, vdot, force);
}

}  // namespace flange::detail
