// Forward dynamics by Featherstone's articulated-body algorithm.
//
// One of flange's two forward algorithms (algorithm.hpp picks one per scene;
// large trees get this one, whose work grows linearly with the links). It
// shares the joints' motions and the scene's constants with Newton–Euler plus
// the mass matrix, but none of their passes, so the two agreeing is a real
// check (other_algorithm.hpp). It runs in the same algebras
// (algebra.hpp): 6-D in space, 3-D (ω_K and the plane's two directions) for a
// planar scene, with motions (ω̇, a) and forces (n, f) at each link's origin
// in link coordinates, accelerations "classic" as in kinematics.hpp:
//
//   down:  c = the velocity-product acceleration of the link at v̇ = 0,
//          p_A = (ω × I·ω, ω × (ω × h)) − loads,   I_A = the link's inertia
//   up:    U = I_A·S, D = Sᵀ·U, u = τ − Sᵀ·p_A,
//          parent's I_A += Xᵀ·(I_A − U·D⁻¹·Uᵀ)·X, p_A += Xᵀ·(p_A + I_a·c + U·D⁻¹·u)
//   down:  a' = X·a_P + c, v̇ = D⁻¹·(u − Uᵀ·a'), a = a' + S·v̇
//
// (where the tree is mostly one chain, v̇ = b − Gᵀ·a_P with b and G formed in
// the step up: aba_link, costs.hpp aba_down_early),
//
// with X the link's motion transform (rotation E, offset p) and a₀ = (0, −g).
// I_A is kept as 3 × 3 blocks in space and as a 3 × 3 matrix in a plane
// (articulated_inertia below). The up and down steps are written once, as
// functions of a link's kinds (its joint's motion, its workspace), not of the
// link: a small scene has them unrolled into the pass, a large one calls one
// shared copy per kind, which stays in the instruction cache
// (aba_shared_steps), and in a plane links in a row of one kind run theirs in
// blocks, handing each other their results in registers (aba_blocks); above
// 16 links each link's (or block's) remaining code is a function of its own
// (links.hpp, for_links_split; for_units_split).
#pragma once
#include "flange/scene/named_state.hpp"
#include "flange/detail/inline.hpp"
#include <array>
#include <cstddef>
#include <new>
#include <tuple>
#include <type_traits>
#include <utility>

#include "flange/dynamics/costs.hpp"
#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/math/congruence.hpp"
#include "flange/math/read_alone.hpp"
#include "flange/math/rotation.hpp"
#include "flange/math/small_matrix.hpp"

namespace flange {

namespace detail {

/// The dimensions of algebra A as (angular or linear, component) pairs.
template <class A>
constexpr auto algebra_dims() {
  if constexpr (A::planar) {
    constexpr int K = A::normal;
    return std::array<std::pair<bool, int>, 3>{{{true, K}, {false, (K + 1) % 3}, {false, (K + 2) % 3}}};
  } else {
    return std::array<std::pair<bool, int>, 6>{{{true, 0}, {true, 1}, {true, 2}, {false, 0}, {false, 1}, {false, 2}}};
  }
}
template <class A>
inline constexpr int algebra_size = int(algebra_dims<A>().size());

template <class A, class T>
using dvec = Eigen::Matrix<T, algebra_size<A>, 1>;
template <class A, class T>
using dmat = Eigen::Matrix<T, algebra_size<A>, algebra_size<A>>;

/// A typed pair (motion or force) as a dense vector of the algebra, and back.
template <class A, class T, class P0, class P1>
FLANGE_INLINE dvec<A, T> to_dense(const P0& ang, const P1& lin) {
  constexpr auto dims = algebra_dims<A>();
  dvec<A, T> r;
  const Vec3<T> a = ang.dense(), l = lin.dense();
  for (int i = 0; i < algebra_size<A>; ++i) r(i) = dims[i].first ? a(dims[i].second) : l(dims[i].second);
  return r;
}
template <class A, class T>
FLANGE_INLINE auto from_dense(const dvec<A, T>& x) {
  constexpr auto dims = algebra_dims<A>();
  Vec3<T> ang = zeros<Vec3<T>>(), lin = zeros<Vec3<T>>();
  for (int i = 0; i < algebra_size<A>; ++i) (dims[i].first ? ang : lin)(dims[i].second) = x(i);
  return motion_pair{to_svec<A::angular_mask>(ang), to_svec<A::linear_mask>(lin)};
}

/// A rigid inertia (m, h, I) as a dense matrix of the algebra: (α, a) ↦ (I·α + h × a, m·a + α × h).
/// Column i is I times the unit motion along dimension i, typed (an axial
/// vector beside a zero one), so that no product with a zero is computed.
template <class A, class T, class R>
FLANGE_INLINE dmat<A, T> inertia_matrix(const R& c) {
  dmat<A, T> I;
  detail::static_for<algebra_size<A>>([&](auto ic) FLANGE_INLINE_LAMBDA {
    constexpr int i = decltype(ic)::value;
    constexpr auto d = algebra_dims<A>()[i];
    const auto F = [&]() FLANGE_INLINE_LAMBDA {
      if constexpr (d.first) return inertia_times(c, motion_pair{axial<T, d.second>(T(1)), zero_vec<T>{}});
      else return inertia_times(c, motion_pair{zero_vec<T>{}, axial<T, d.second>(T(1))});
    }();
    const dvec<A, T> col = to_dense<A, T>(F.n, F.f);
    for (int k = 0; k < algebra_size<A>; ++k) I(k, i) = col(k);
  });
  return I;
}

/// fit<M>(v): v as an svec of mask M. Components of M that v does not hold
/// are constant zeros; components of v outside M are dropped (the caller
/// knows they are zero, or, in a plane, that they never reach q̈).
template <int M, class T, int N>
FLANGE_INLINE svec<T, M> fit(const svec<T, N>& v) {
  svec<T, M> r;
  for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (bit(M, I)) r.template at<I>() = v.template get<I>();
  });
  return r;
}

/// Motions and forces with the algebra's components (all six in space;
/// ω_K and the plane's two directions in a plane), in link coordinates.
template <class A, class T>
using aba_motion = motion_pair<svec<T, A::angular_mask>, svec<T, A::linear_mask>>;
template <class A, class T>
using aba_force = force_pair<svec<T, A::angular_mask>, svec<T, A::linear_mask>>;
template <class A, class T, class Ang, class Lin>
FLANGE_INLINE aba_motion<A, T> as_motion(const Ang& ang, const Lin& lin) {
  return {fit<A::angular_mask>(ang), fit<A::linear_mask>(lin)};
}
template <class A, class T, class N, class F>
FLANGE_INLINE aba_force<A, T> as_force(const N& n, const F& f) {
  return {fit<A::angular_mask>(n), fit<A::linear_mask>(f)};
}

/// An articulated-body inertia: the symmetric map from a link's acceleration
/// (α, a) to the force (n, f) its subtree resists with. In space it is kept
/// as three 3 × 3 blocks, n = Θ·α + H·a, f = Hᵀ·α + M·a, and carried to the
/// parent block by block: a rotation (Eᵀ·X·E for each block, applied as the
/// link's rotation type allows, math/congruence.hpp) and then the shift by the
/// child's offset p,
///
///   H' = H + p̂·M,  Θ' = Θ + p̂·Hᵀ − H'·p̂,  M' = M,
///
/// with p̂· as cross products. Θ and M are symmetric, and every step that
/// changes them (the rotation, Θ's shift, the subtraction of U·D⁻¹·Uᵀ)
/// computes their upper triangle and mirrors it: 16-link spatial chain,
/// 1693 → 1560 instructions a link. In a plane it is a symmetric 3 × 3 matrix
/// over (α_K, a_i, a_j), carried by the link's motion transform in blocks
/// (add_from_child below).
///
/// After I_a = I_A − U·D⁻¹·Uᵀ, I_a·S = 0. For a joint of one rate along a
/// coordinate direction (S = ±e_ZA angular: a revolute joint in its axis
/// frame; ±e_ZL linear: a prismatic one; known_zero_dims below) that zeroes
/// whole rows: Θ's row and column ZA and H's row ZA, or M's row and column
/// ZL and H's column ZL. subtract, times and add_from_child take ZA and ZL
/// (−1: none): they set those entries to zero instead of computing the
/// cancellation, skip them as factors, and turn Θ and H about the joint's own
/// axis (its rotation's first factor) in the 2 × 2 block that is left
/// (math/congruence.hpp).
template <class A, class T>
struct articulated_inertia;

/// The angular and the linear dimension a joint's single motion column is
/// (−1: none, or the joint has several rates).
template <class Mo, int NV>
constexpr std::pair<int, int> known_zero_dims() {
  if constexpr (NV != 1) {
    return {-1, -1};
  } else {
    using C = decltype(std::declval<const Mo&>().template col<0>());
    constexpr int am = std::remove_cvref_t<decltype(std::declval<C>().ang)>::mask;
    constexpr int lm = std::remove_cvref_t<decltype(std::declval<C>().lin)>::mask;
    constexpr auto single = [](int m) { return m == 1 ? 0 : m == 2 ? 1 : m == 4 ? 2 : -1; };
    if constexpr (lm == 0 && single(am) >= 0) return {single(am), -1};
    else if constexpr (am == 0 && single(lm) >= 0) return {-1, single(lm)};
    else return {-1, -1};
  }
}

template <class T>
struct articulated_inertia<spatial_algebra, T> {
  using A = spatial_algebra;
  Mat3<T> Th, H, M;

  template <class R>
  FLANGE_INLINE static articulated_inertia rigid(const R& r) {
    articulated_inertia a{to_matrix<T>(r.I_o), tilde<T>(r.h.dense()), {}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a.M(i, j) = i == j ? r.m : T(0);
    return a;
  }
  template <int ZA = -1, int ZL = -1, class Ang, class Lin>
  FLANGE_INLINE aba_force<A, T> times(const Ang& al, const Lin& a) const {
    constexpr int NA = ZA < 0 ? 7 : 7 & ~(1 << ZA), NL = ZL < 0 ? 7 : 7 & ~(1 << ZL);
    const auto alz = fit<Ang::mask & NA>(al);
    const auto az = fit<Lin::mask & NL>(a);
    return as_force<A, T>(fit<NA>(Th * alz + H * az), fit<NL>(rot_t(H, alz) + M * az));
  }
  /// The yardstick of a pivot: the trace of the blocks a column moves in.
  FLANGE_INLINE T scale(bool ang, bool lin) const { return (ang ? Th.trace() : T(0)) + (lin ? M.trace() : T(0)); }
  /// −= Σ U_i·W_iᵀ, for force columns U and W whose sum is symmetric (U·D⁻¹
  /// and U in practice, so Θ and M are updated as symmetric).
  template <int ZA = -1, int ZL = -1, std::size_t N>
  FLANGE_INLINE void subtract(const std::array<aba_force<A, T>, N>& U, const std::array<aba_force<A, T>, N>& W) {
    for (std::size_t k = 0; k < N; ++k) {
      const Vec3<T> un = U[k].n.dense(), uf = U[k].f.dense(), wn = W[k].n.dense(), wf = W[k].f.dense();
      small::sub_outer_sym<ZA>(Th, un, wn);
      small::sub_outer<ZA, ZL>(H, un, wf);
      small::sub_outer_sym<ZL>(M, uf, wf);
    }
  }
  template <int ZA = -1, int ZL = -1, class Mo>
  FLANGE_INLINE void add_from_child(const articulated_inertia& c, const Mo& m) {
    const Mat3<T> Thr = rotated_back_sym<T, ZA>(m.E(), c.Th), Hr = rotated_back<T, ZA>(m.E(), c.H),
                  Mr = rotated_back_sym<T, ZL>(m.E(), c.M);
    small::add_to(M, Mr);
    if constexpr (is_zero_vec<decltype(m.p)>) {
      small::add_to(Th, Thr);
      small::add_to(H, Hr);
    } else {
      const Vec3<T> p = m.p.dense();
      Mat3<T> Hs = Hr;
      small::add_to(Hs, small::skew_mul(p, Mr));
      small::add_shift_sym(Th, Thr, p, Hr, Hs);
      small::add_to(H, Hs);
    }
  }
};

template <int K, class T>
struct articulated_inertia<planar_algebra<K>, T> {
  using A = planar_algebra<K>;
  dmat<A, T> I;

  template <class R>
  FLANGE_INLINE static articulated_inertia rigid(const R& r) {
    return {inertia_matrix<A, T>(r)};
  }
  /// The algebra's dimension a known-zero angular ZA or linear ZL is (−1: none).
  static constexpr int zero_dim(int ZA, int ZL) {
    return ZA == K ? 0 : ZL == (K + 1) % 3 ? 1 : ZL == (K + 2) % 3 ? 2 : -1;
  }
  template <int ZA = -1, int ZL = -1, class Ang, class Lin>
  FLANGE_INLINE aba_force<A, T> times(const Ang& al, const Lin& a) const {
    // I·x with row and column d (the known-zero dimension) left out, and
    // the columns of x's typed zeros (a joint's motion column: U = I·S is
    // then a column of I, with no product by 0.0 on the path to D⁻¹).
    constexpr int d = zero_dim(ZA, ZL);
    constexpr auto dims = algebra_dims<A>();
    constexpr auto held = [&] {
      std::array<bool, 3> h{};
      for (int k = 0; k < 3; ++k)
        h[k] = k != d && bit(dims[k].first ? Ang::mask : Lin::mask, dims[k].second);
      return h;
    }();
    const dvec<A, T> x = to_dense<A, T>(al, a);
    dvec<A, T> y;
    detail::static_for<3>([&](auto r) FLANGE_INLINE_LAMBDA {
      constexpr int R = decltype(r)::value;
      constexpr int first = held[0] ? 0 : held[1] ? 1 : held[2] ? 2 : -1;
      if constexpr (R == d || first < 0) {
        y(R) = T(0);
      } else {
        y(R) = I(R, first) * x(first);
        detail::static_for<3>([&](auto c) FLANGE_INLINE_LAMBDA {
          constexpr int C = decltype(c)::value;
          if constexpr (C > first && held[C]) y(R) += I(R, C) * x(C);
        });
      }
    });
    // Written into the force's components one by one: a copy of the
    // linear pair went through the stack (two 8-byte stores read back as
    // one 16-byte load, which stalls).
    aba_force<A, T> f;
    detail::static_for<3>([&](auto k) FLANGE_INLINE_LAMBDA {
      constexpr auto dk = dims[decltype(k)::value];
      if constexpr (dk.first) f.n.template at<dk.second>() = y(decltype(k)::value);
      else f.f.template at<dk.second>() = y(decltype(k)::value);
    });
    return f;
  }
  FLANGE_INLINE T scale(bool ang, bool lin) const {
    return (ang ? I(0, 0) : T(0)) + (lin ? I(1, 1) + I(2, 2) : T(0));
  }
  template <int ZA = -1, int ZL = -1, std::size_t N>
  FLANGE_INLINE void subtract(const std::array<aba_force<A, T>, N>& U, const std::array<aba_force<A, T>, N>& W) {
    for (std::size_t k = 0; k < N; ++k)
      small::sub_outer_sym<zero_dim(ZA, ZL)>(I, to_dense<A, T>(U[k].n, U[k].f), to_dense<A, T>(W[k].n, W[k].f));
  }
  /// Xᵀ·I·X for the link's motion transform X = [[1, 0], [E₂·q, E₂]]
  /// (E₂ the rotation in the plane, q = e_K × p), in blocks: with
  /// h' = E₂ᵀ·h and M' = E₂ᵀ·M·E₂ (M the 2 × 2 block over a_i, a_j),
  ///   θ + 2·h'·q + qᵀ·M'·q,   h' + M'·q,   M'.
  /// Behind a revolute joint (ZA = K) θ and h are known zero: θ' = qᵀ·M'·q
  /// and h' = M'·q.
  template <int ZA = -1, int ZL = -1, class Mo>
  FLANGE_INLINE void add_from_child(const articulated_inertia& c, const Mo& m) {
    constexpr bool turn_only = zero_dim(ZA, ZL) == 0;
    constexpr int i = (K + 1) % 3, j = (K + 2) % 3;
    const auto pair = [](const T& x, const T& y) FLANGE_INLINE_LAMBDA {
      svec<T, A::linear_mask> v;
      v.template at<i>() = x;
      v.template at<j>() = y;
      return v;
    };
    const auto a0 = rot_t(m.E(), pair(c.I(1, 1), c.I(2, 1))), a1 = rot_t(m.E(), pair(c.I(1, 2), c.I(2, 2)));
    const auto r0 = rot_t(m.E(), pair(a0.template get<i>(), a1.template get<i>()));
    const T m00 = r0.template get<i>(), m01 = r0.template get<j>();
    const T m11 = rot_t(m.E(), pair(a0.template get<j>(), a1.template get<j>())).template get<j>();
    if constexpr (turn_only) {
      if constexpr (!is_zero_vec<decltype(m.p)>) {
        const T qi = -m.p.template get<j>(), qj = m.p.template get<i>();
        const T mqi = m00 * qi + m01 * qj, mqj = m01 * qi + m11 * qj;
        I(0, 0) += qi * mqi + qj * mqj;
        I(1, 0) = I(0, 1) += mqi;
        I(2, 0) = I(0, 2) += mqj;
      }
    } else {
      const auto h = rot_t(m.E(), pair(c.I(1, 0), c.I(2, 0)));
      T th = c.I(0, 0), hi = h.template get<i>(), hj = h.template get<j>();
      if constexpr (!is_zero_vec<decltype(m.p)>) {
        const T qi = -m.p.template get<j>(), qj = m.p.template get<i>();
        const T mqi = m00 * qi + m01 * qj, mqj = m01 * qi + m11 * qj;
        th += T(2) * (hi * qi + hj * qj) + (qi * mqi + qj * mqj);
        hi += mqi;
        hj += mqj;
      }
      I(0, 0) += th;
      I(1, 0) = I(0, 1) += hi;
      I(2, 0) = I(0, 2) += hj;
    }
    I(1, 1) += m00;
    I(2, 1) = I(1, 2) += m01;
    I(2, 2) += m11;
  }
};

/// read_alone (math/read_alone.hpp) for an articulated inertia and a force.
/// Only planar steps read their records alone (aba_up; blocks are planar,
/// costs.hpp aba_block_links): a spatial record is worked on in place.
template <int K, class T>
FLANGE_INLINE articulated_inertia<planar_algebra<K>, T> read_alone(const articulated_inertia<planar_algebra<K>, T>& a) {
  return {flange::read_alone(a.I)};
}
template <class N, class F>
FLANGE_INLINE force_pair<N, F> read_alone(const force_pair<N, F>& f) {
  return {flange::read_alone(f.n), flange::read_alone(f.f)};
}

template <class A, class T, int NV, bool Early>
struct aba_link {
  // Not zeroed: every entry is written before it is read (the workspace is a
  // tuple, which would otherwise value-initialise it at every evaluation, and
  // the tests' NaN-filled stacks would not see a read before a write).
  aba_link() {}
  svec<T, A::angular_mask> w;  ///< ω
  articulated_inertia<A, T> IA;
  aba_force<A, T> pA;
  aba_motion<A, T> c, a;
  /// What the step down takes from the step up, in one of two forms
  /// (costs.hpp, aba_down_early; the scene chooses, aba_workspace):
  ///  early:  v̇ = b − Gᵀ·a_P, with b = D⁻¹·(u − Uᵀ·c) and G = Xᵀ·U·D⁻¹ (by
  ///          column, a force in the parent's coordinates), formed in the
  ///          step up, where they wait for nothing;
  ///  late:   v̇ = D⁻¹·(b − Gᵀ·a'), a' = X·a_P + c, with b = u and G = U.
  static constexpr bool early = Early;
  std::array<T, NV> b;
  std::array<aba_force<A, T>, NV> G;
  struct none {};
  [[no_unique_address]] std::conditional_t<early, none, Eigen::Matrix<T, NV, NV>> Dinv;
};

/// The most links from the World to a leaf.
template <class S>
constexpr int tree_depth() {
  constexpr int NL = S::tree.n_links;
  std::array<int, NL> d{};
  int most = 0;
  for (int L = 1; L < NL; ++L) {  // parents come first
    d[L] = d[S::tree.link_parent[L]] + 1;
    most = d[L] > most ? d[L] : most;
  }
  return most;
}
template <class A, class S, class T, class Seq = std::make_integer_sequence<int, S::tree.n_links - 1>>
struct aba_workspace;
template <class A, class S, class T, int... L>
struct aba_workspace<A, S, T, std::integer_sequence<int, L...>> {
  static constexpr bool early = aba_down_early(A::planar, tree_depth<S>(), S::tree.n_links - 1);
  using type = std::tuple<aba_link<A, T, link_info<S, L + 1>::nv, early>...>;
};

/// The articulated body's instructions when its steps are unrolled into one
/// function: the sum of each link's (costs.hpp).
template <class A, class S>
constexpr int aba_unrolled_instructions() {
  constexpr auto& k = aba_unrolled_link;
  return []<int... L>(std::integer_sequence<int, L...>) {
    return (0 + ... + (A::planar ? k.planar : general_rotation<S, L + 1>() ? k.general : k.typed));
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}
/// Whether the per-link steps run as shared functions, one per kind of link
/// (aba_up_shared, aba_down_shared, and aba_start_shared in space), rather
/// than unrolled into the pass: when the unrolled code would pass a number of
/// instructions (costs.hpp: 5,000 in space, 7,500 in a plane). Beyond that
/// it outgrows the processor's caches of decoded instructions, and the time
/// per link rose by half while the instructions per link did not
/// (docs/performance.md); below it the calls only cost. This puts the switch
/// at 6 links in space (typed or run-time axes) and 18 in a plane.
template <class A, class S>
constexpr bool aba_shared_steps() {
  return aba_unrolled_instructions<A, S>() >
         (A::planar ? aba_shared_steps_above.planar : aba_shared_steps_above.spatial);
}

/// D⁻¹ for D = Sᵀ·I_A·S, with the relative pivot test of ldlt.hpp against the
/// trace of the articulated inertia's blocks each column moves in. Returns
/// the first failing pivot (index among the joint's rates), for the caller to
/// report with the joint's name.
template <class A, class T, class Mo, std::size_t NV>
FLANGE_INLINE pivot_report<T> aba_invert_d(const std::array<aba_force<A, T>, NV>& U, const articulated_inertia<A, T>& IA,
                                           const Mo& m, Eigen::Matrix<T, int(NV), int(NV)>& Dinv) {
  constexpr int nv = int(NV);
  Eigen::Matrix<T, nv, nv> D;
  std::array<T, nv> scale;
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    (
        [&]() FLANGE_INLINE_LAMBDA {
          const auto s = m.template col<K>();
          const auto g = m.project(U[K].n, U[K].f);
          for (int i = 0; i < nv; ++i) D(i, K) = g[i];
          scale[K] = IA.scale(!is_zero_vec<decltype(s.ang)>, !is_zero_vec<decltype(s.lin)>);
        }(),
        ...);
  }(std::make_integer_sequence<int, nv>{});
  ldlt_pivots<nv, T> f;
  if (const auto p = ldlt_factor<nv>(D, f, scale.data()); p.index >= 0) [[unlikely]]
    return p;
  for (int k = 0; k < nv; ++k) {
    std::array<T, nv> e{}, col{};
    e[k] = T(1);
    ldlt_solve<nv>(D, f, e.data(), col.data());
    for (int i = 0; i < nv; ++i) Dinv(i, k) = col[i];
  }
  return {};
}

/// One link's first step, down the tree: its ω from the parent's wP, its
/// velocity-product acceleration c (forward_step from the parent's ω alone),
/// its bias force p_A, and its own inertia (the model's record I, of kinds
/// HZero, IKind: link_inertia_of) as the start of I_A. Like the other steps,
/// a function of the link's kinds, shared between links in a large scene.
template <class A, class T, bool HZero, int IKind, bool Torque, bool Force, class W, class Mo, class WP>
FLANGE_INLINE void aba_start(W& w, const Mo& m, const WP& wP, const rigid_inertia<double>& I, const T* v,
                             const Vec3<T>& n_ext, const Vec3<T>& f_ext) {
  const auto k = forward_step<T>(link_kinematics{wP, zero_vec<T>{}, zero_vec<T>{}}, m, v, no_rates{});
  w.w = fit<A::angular_mask>(k.w);
  w.c = as_motion<A, T>(k.wd, k.a);
  const auto pA = own_wrench_of<A, T, Torque, Force>(link_inertia_of<A, T, HZero, IKind>(I),
                                                      link_kinematics{k.w, zero_vec<T>{}, zero_vec<T>{}}, n_ext, f_ext);
  w.pA = as_force<A, T>(pA.n, pA.f);
  // Built in place (the prvalue initialises w.IA itself), not assigned:
  // GCC left the record's assignment out of line in a large translation
  // unit (the scale benchmark's chains), a call per link and the spills
  // around it (8-link spatial chain 806 → 1390 ns).
  using inertia_type = articulated_inertia<A, T>;
  ::new (static_cast<void*>(&w.IA)) inertia_type(inertia_type::rigid(link_inertia_of<A, T, HZero, IKind>(I)));
}

/// A link's step up given its I_A and p_A (its children's shares added):
/// the parent's shares go to *ip and *fp (nullptr: no parent), which are the
/// parent's record or, in a block of links (aba_up_block), the values the
/// next step takes in registers.
template <class A, class T, bool JointForces, class W, class Mo, class IA_, class PA_, class IP, class FP>
FLANGE_INLINE pivot_report<T> aba_up_carry(W& w, const Mo& m, IA_& IA, const PA_& pA, IP* ip, FP* fp, const T* tau) {
  constexpr int nv = std::tuple_size_v<decltype(w.b)>;
  // U = I_A·S, D⁻¹, u, U·D⁻¹: in the early form this step's own (the step
  // down takes b and G); in the late form U, D⁻¹ and u are written where the
  // step down reads them.
  std::array<aba_force<A, T>, nv> UDinv, U_own;
  Eigen::Matrix<T, nv, nv> Dinv_own;
  std::array<T, nv> u_own;
  auto& U = [&]() FLANGE_INLINE_LAMBDA -> auto& {
    if constexpr (W::early) return U_own;
    else return w.G;
  }();
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    ((U[K] = IA.times(m.template col<K>().ang, m.template col<K>().lin)), ...);
  }(std::make_integer_sequence<int, nv>{});
  auto& Dinv = [&]() FLANGE_INLINE_LAMBDA -> auto& {
    if constexpr (W::early) return Dinv_own;
    else return w.Dinv;
  }();
  if (const auto piv = aba_invert_d(U, IA, m, Dinv); piv.index >= 0) [[unlikely]]
    return piv;
  auto& u = [&]() FLANGE_INLINE_LAMBDA -> auto& {
    if constexpr (W::early) return u_own;
    else return w.b;
  }();
  const auto sp = m.project(pA.n, pA.f);
  for (int k = 0; k < nv; ++k) {
    if constexpr (JointForces) u[k] = tau[k] - sp[k];
    else u[k] = -sp[k];
  }
  for (int k = 0; k < nv; ++k) {
    auto n = Dinv(0, k) * U[0].n;
    auto f = Dinv(0, k) * U[0].f;
    for (int i = 1; i < nv; ++i) {
      n = n + Dinv(i, k) * U[i].n;
      f = f + Dinv(i, k) * U[i].f;
    }
    UDinv[k] = {n, f};
  }
  if constexpr (W::early) {
    // The step down's v̇ = D⁻¹·(u − Uᵀ·(X·a_P + c)) as b − Gᵀ·a_P (aba_down).
    std::array<T, nv> r;
    for (int k = 0; k < nv; ++k)
      r[k] = u[k] - (value_of<T>(dot(U[k].n, w.c.ang)) + value_of<T>(dot(U[k].f, w.c.lin)));
    for (int i = 0; i < nv; ++i) {
      w.b[i] = Dinv(i, 0) * r[0];
      for (int k = 1; k < nv; ++k) w.b[i] += Dinv(i, k) * r[k];
      const auto g = carry_up(m, force_pair{UDinv[i].n, UDinv[i].f});
      w.G[i] = as_force<A, T>(g.n, g.f);
    }
  }
  if constexpr (!std::is_same_v<IP, std::nullptr_t>) {
    // I_a = I_A − U·D⁻¹·Uᵀ; p_a = p_A + I_a·c + U·D⁻¹·u
    constexpr auto Z = known_zero_dims<Mo, nv>();
    IA.template subtract<Z.first, Z.second>(UDinv, U);
    const auto Iac = IA.template times<Z.first, Z.second>(w.c.ang, w.c.lin);
    auto pn = pA.n + Iac.n;
    auto pf = pA.f + Iac.f;
    for (int k = 0; k < nv; ++k) {
      pn = pn + u[k] * UDinv[k].n;
      pf = pf + u[k] * UDinv[k].f;
    }
    ip->template add_from_child<Z.first, Z.second>(IA, m);
    const auto up = carry_up(m, force_pair{pn, pf});
    *fp = as_force<A, T>(fp->n + up.n, fp->f + up.f);
  }
  return {};
}

/// aba_up_carry with the parent's shares going to the record of parent p
/// (nullptr: none).
template <class A, class T, bool JointForces, class W, class Mo, class IA_, class PA_, class P>
FLANGE_INLINE pivot_report<T> aba_up_to(W& w, const Mo& m, IA_& IA, const PA_& pA, P* p, const T* tau) {
  if constexpr (std::is_same_v<P, std::nullptr_t>) return aba_up_carry<A, T, JointForces>(w, m, IA, pA, p, p, tau);
  else return aba_up_carry<A, T, JointForces>(w, m, IA, pA, &p->IA, &p->pA, tau);
}

/// One link's step up the tree: U = I_A·S, D⁻¹, u = τ − Sᵀ·p_A, the step
/// down's b and G, and, with a parent p (not nullptr), the parent's
/// I_A += Xᵀ·(I_A − U·D⁻¹·Uᵀ)·X and p_A += Xᵀ·(p_A + I_a·c + U·D⁻¹·u). Its
/// types are the link's kinds, not the link: links of one kind share one copy
/// of it in a large scene (aba_shared_steps). Returns D⁻¹'s failing pivot,
/// if any.
template <class A, class T, bool JointForces, class W, class Mo, class P>
FLANGE_INLINE pivot_report<T> aba_up(W& w, const Mo& m, P* p, const T* tau) {
  // I_A and p_A were just written by the children's steps, entry by entry.
  // In a plane (9 and 3 numbers) they are read alone (math/read_alone.hpp)
  // and worked on in registers, I_a and p_a going to the parent only; in
  // space (27 and 6) they stay in the link's record, where they are worked
  // on in place: copied out, they spilled (16-link chain, run-time axes:
  // 1134 against 1081 ns).
  auto&& IA = [&]() FLANGE_INLINE_LAMBDA -> decltype(auto) {
    if constexpr (A::planar) return read_alone(w.IA);
    else return (w.IA);
  }();
  auto&& pA = [&]() FLANGE_INLINE_LAMBDA -> decltype(auto) {
    if constexpr (A::planar) return read_alone(w.pA);
    else return (w.pA);
  }();
  return aba_up_to<A, T, JointForces>(w, m, IA, pA, p, tau);
}

/// One link's step down the tree from its parent's acceleration aP:
/// v̇ = D⁻¹·(u − Uᵀ·a') into vdot, a' = X·a_P + c, and, for a link with
/// children, returns a = a' + S·v̇, kept in its record if StoreA (a block of
/// links, aba_down_block, hands it to the next step in registers). Shared
/// between links of one kind like aba_up.
template <class A, class T, bool HasChildren, bool StoreA = HasChildren, class W, class Mo, class AP>
FLANGE_INLINE auto aba_down(W& w, const Mo& m, const AP& aP, T* vdot) {
  constexpr int nv = std::tuple_size_v<decltype(w.b)>;
  // v̇ = D⁻¹·(u − Uᵀ·a') with a' = X·a_P + c; in the early form (aba_link)
  // as b − Gᵀ·a_P: the chain of accelerations that runs down a long chain
  // link after link then waits for a dot product and a subtraction a link,
  // not for the rotation and D⁻¹ too (planar 32-link chain: 998 → 869 ns).
  const auto parent_part = [&]() FLANGE_INLINE_LAMBDA {  // a' = X·a_P + c
    return as_motion<A, T>(rot(m.E(), aP.ang) + w.c.ang, rot(m.E(), aP.lin + cross(aP.ang, m.p)) + w.c.lin);
  };
  const auto minus_g = [&](const auto& x, std::array<T, nv>& r) FLANGE_INLINE_LAMBDA {  // b − Gᵀ·x
    for (int i = 0; i < nv; ++i)
      r[i] = w.b[i] - (value_of<T>(dot(w.G[i].n, x.ang)) + value_of<T>(dot(w.G[i].f, x.lin)));
  };
  // Formed once, before v̇ is written (vdot may alias what a' reads).
  const auto ap = [&]() FLANGE_INLINE_LAMBDA {
    if constexpr (!W::early || HasChildren) return parent_part();
    else return 0;
  }();
  std::array<T, nv> acc;
  if constexpr (W::early) {
    minus_g(aP, acc);
  } else {
    std::array<T, nv> r;
    minus_g(ap, r);
    for (int i = 0; i < nv; ++i) {
      acc[i] = w.Dinv(i, 0) * r[0];
      for (int k = 1; k < nv; ++k) acc[i] += w.Dinv(i, k) * r[k];
    }
  }
  for (int i = 0; i < nv; ++i) vdot[i] = acc[i];
  if constexpr (HasChildren) {
    auto an = ap.ang;
    auto al = ap.lin;
    [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
      ((an = fit<A::angular_mask>(an + acc[K] * m.template col<K>().ang),
        al = fit<A::linear_mask>(al + acc[K] * m.template col<K>().lin)),
       ...);
    }(std::make_integer_sequence<int, nv>{});
    const aba_motion<A, T> a{an, al};
    if constexpr (StoreA) w.a = a;
    return a;
  } else {
    return 0;
  }
}

/// The steps up and down of a block of R links in a row (aba_blocks): link
/// k's parent is link k − 1, the first one's is p (or aP), and links of a
/// block have one kind. One step hands the next its result in registers
/// (I_A and p_A up, a down) where separate steps pass them through memory,
/// and one call does R links' steps. wp and mp list the links' records and
/// motions, first to last; the step up runs last to first. The failing
/// pivot's index counts the block's rates from the first link's.
template <class A, class T, bool HZero, int IKind, bool Torque, bool Force, int R, class W, class Mo, class WP>
FLANGE_INLINE void aba_start_block(W* const* wp, const Mo* const* mp, const WP& wP, const rigid_inertia<double>* I,
                                   const T* v, const Vec3<T>* n_ext, const Vec3<T>* f_ext) {
  constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
  aba_start<A, T, HZero, IKind, Torque, Force>(*wp[0], *mp[0], wP, I[0], v, n_ext[0], f_ext[0]);
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    (aba_start<A, T, HZero, IKind, Torque, Force>(*wp[K + 1], *mp[K + 1], wp[K]->w, I[K + 1], v + (K + 1) * nv,
                                                  n_ext[K + 1], f_ext[K + 1]),
     ...);
  }(std::make_integer_sequence<int, R - 1>{});
}
template <class A, class T, bool JointForces, int R, class W, class Mo, class P>
FLANGE_INLINE pivot_report<T> aba_up_block(W* const* wp, const Mo* const* mp, P* p, const T* tau) {
  constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
  auto IA = read_alone(wp[R - 1]->IA);
  auto pA = read_alone(wp[R - 1]->pA);
  pivot_report<T> piv{};
  const bool ok = [&]<int... J>(std::integer_sequence<int, J...>) FLANGE_INLINE_LAMBDA {
    return ([&]() FLANGE_INLINE_LAMBDA {
      constexpr int k = R - 1 - J;
      if constexpr (k > 0) {
        auto IAn = read_alone(wp[k - 1]->IA);
        auto pAn = read_alone(wp[k - 1]->pA);
        piv = aba_up_carry<A, T, JointForces>(*wp[k], *mp[k], IA, pA, &IAn, &pAn, tau + k * nv);
        IA = IAn;
        pA = pAn;
      } else {
        piv = aba_up_to<A, T, JointForces>(*wp[0], *mp[0], IA, pA, p, tau);
      }
      if (piv.index >= 0) [[unlikely]] {
        piv.index += k * nv;
        return false;
      }
      return true;
    }() && ...);
  }(std::make_integer_sequence<int, R>{});
  if (!ok) [[unlikely]]
    return piv;
  return {};
}
template <class A, class T, bool LastHasChildren, int R, class W, class Mo, class AP>
FLANGE_INLINE void aba_down_block(W* const* wp, const Mo* const* mp, const AP& aP, T* vdot) {
  constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
  auto a = aba_down<A, T, true, false>(*wp[0], *mp[0], aP, vdot);
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    ((a = aba_down<A, T, true, false>(*wp[K + 1], *mp[K + 1], a, vdot + (K + 1) * nv)), ...);
  }(std::make_integer_sequence<int, R - 2>{});
  aba_down<A, T, LastHasChildren>(*wp[R - 1], *mp[R - 1], a, vdot + (R - 1) * nv);
}

/// The same steps as functions of their own, one per combination of kinds:
/// a large scene's links then run the same instructions, which stay in the
/// instruction cache, where one unrolled copy per link did not
/// (aba_shared_steps).
template <class A, class T, bool HZero, int IKind, bool Torque, bool Force, class W, class Mo, class WP>
[[gnu::noinline]] void aba_start_shared(W& w, const Mo& m, const WP& wP, const rigid_inertia<double>& I, const T* v,
                                        const Vec3<T>& n_ext, const Vec3<T>& f_ext) {
  aba_start<A, T, HZero, IKind, Torque, Force>(w, m, wP, I, v, n_ext, f_ext);
}
template <class A, class T, bool JointForces, class W, class Mo, class P>
[[gnu::noinline]] pivot_report<T> aba_up_shared(W& w, const Mo& m, P* p, const T* tau) {
  return aba_up<A, T, JointForces>(w, m, p, tau);
}
template <class A, class T, bool HasChildren, class W, class Mo, class AP>
[[gnu::noinline]] void aba_down_shared(W& w, const Mo& m, const AP& aP, T* vdot) {
  aba_down<A, T, HasChildren>(w, m, aP, vdot);
}
template <class A, class T, bool HZero, int IKind, bool Torque, bool Force, int R, class W, class Mo, class WP>
[[gnu::noinline]] void aba_start_block_shared(W* const* wp, const Mo* const* mp, const WP& wP,
                                              const rigid_inertia<double>* I, const T* v, const Vec3<T>* n_ext,
                                              const Vec3<T>* f_ext) {
  aba_start_block<A, T, HZero, IKind, Torque, Force, R>(wp, mp, wP, I, v, n_ext, f_ext);
}
template <class A, class T, bool JointForces, int R, class W, class Mo, class P>
[[gnu::noinline]] pivot_report<T> aba_up_block_shared(W* const* wp, const Mo* const* mp, P* p, const T* tau) {
  return aba_up_block<A, T, JointForces, R>(wp, mp, p, tau);
}
template <class A, class T, bool LastHasChildren, int R, class W, class Mo, class AP>
[[gnu::noinline]] void aba_down_block_shared(W* const* wp, const Mo* const* mp, const AP& aP, T* vdot) {
  aba_down_block<A, T, LastHasChildren, R>(wp, mp, aP, vdot);
}

/// The scene's links in blocks for the steps up and down (aba_up_block):
/// runs of at most MaxLen links in a row, each link the only child of the one
/// before it, of one kind (record and motion types, inertia kinds, loads),
/// their rates one after another, none freeing every direction. Each unit is (start, len); a unit
/// of one link runs the link's own step.
template <class A, class S, class T, int MaxLen>
struct aba_blocks {
  static constexpr int NL = S::tree.n_links;
  using WS = typename aba_workspace<A, S, T>::type;
  using MS = std::remove_cvref_t<decltype(algebra_motions<A>(std::declval<const S&>(), std::declval<const T*>()))>;
  /// Element I of tuple X, found as std::get finds it (std::tuple_element
  /// would instantiate a class per few elements for every lookup: the
  /// 128-link chain's test compiled in 143 s instead of 128).
  template <class X, int I>
  using element = std::remove_cvref_t<decltype(std::get<I>(std::declval<X&>()))>;
  template <int L>
  static constexpr bool frees_all = link_info<S, L>::parent != 0 && link_info<S, L>::nv == algebra_size<A>;
  /// Whether link L can follow link L − 1 in a block.
  template <int L>
  static constexpr bool joins() {
    if constexpr (L < 2) {
      return false;
    } else {
      using LI = link_info<S, L>;
      using LP = link_info<S, L - 1>;
      constexpr auto K = inertia_kinds<S>::value;
      constexpr auto F = load_flags<S>::value;
      return LI::parent == L - 1 && children<S, L - 1>().size() == 1 && LI::v == LP::v + LP::nv && !frees_all<L> &&
             !frees_all<L - 1> && std::is_same_v<element<WS, L - 1>, element<WS, L - 2>> &&
             std::is_same_v<element<MS, L - 1>, element<MS, L - 2>> && K.h_zero[L] == K.h_zero[L - 1] &&
             K.I_kind[L] == K.I_kind[L - 1] && F.torque[L] == F.torque[L - 1] && F.force[L] == F.force[L - 1];
    }
  }
  struct table {
    std::array<int, NL> start{}, len{};
    int n = 0;
  };
  static constexpr table value = [] {
    // No blocks (MaxLen 1, as in space): nothing to look at.
    constexpr auto j = []<int... I>(std::integer_sequence<int, I...>) {
      if constexpr (MaxLen == 1) return std::array<bool, NL>{};
      else return std::array<bool, NL>{joins<I>()...};
    }(std::make_integer_sequence<int, NL>{});
    table t{};
    for (int L = 1; L < NL;) {
      int len = 1;
      while (L + len < NL && len < MaxLen && j[L + len]) ++len;
      t.start[t.n] = L;
      t.len[t.n] = len;
      ++t.n;
      L += len;
    }
    return t;
  }();
};

/// f(integral_constant<U>) for the units U = 0 … N − 1 (Reverse: N − 1 … 0),
/// each its own function in a large scene, as for_links_split.
template <class S, int N, bool Reverse = false, class F>
FLANGE_INLINE void for_units_split(F&& f) {
  [&]<int... U>(std::integer_sequence<int, U...>) FLANGE_INLINE_LAMBDA {
    if constexpr (!split_links<S>) {
      if constexpr (Reverse) (f(std::integral_constant<int, N - 1 - U>{}), ...);
      else (f(std::integral_constant<int, U>{}), ...);
    } else {
      if constexpr (Reverse) (link_step<N - 1 - U>(f), ...);
      else (link_step<U>(f), ...);
    }
  }(std::make_integer_sequence<int, N>{});
}

}  // namespace detail

/// How the articulated body's per-link steps are compiled: unrolled into one
/// function, as functions shared by links of one kind, or as
/// detail::aba_shared_steps decides from the scene's size. The tests run both
/// on one scene; users keep the default.
enum class aba_steps { automatic, unrolled, shared };

/// v̇ at (t, q, v) by the articulated-body algorithm, in algebra A.
template <class A, aba_steps Steps = aba_steps::automatic, class S, class T>
void accelerations_articulated_body_in(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  using namespace detail;
  constexpr bool shared =
      Steps == aba_steps::shared || (Steps == aba_steps::automatic && aba_shared_steps<A, S>());
  const auto xs = state_view<S>(q, v);
  typename aba_workspace<A, S, T>::type ws;
  const auto motions = algebra_motions<A>(scene, q);
  link_loads<S, T> n_ext, f_ext;
  gather_external<A>(scene, t, xs, motions, pose_motions<A>(scene, q, motions), n_ext, f_ext);
  std::array<T, S::n_v> tau;
  if constexpr (has_joint_forces<S>()) joint_forces(scene, t, xs, tau.data());
  // Each pass runs a link at a time, or blocks of links in a row when the
  // steps are shared (aba_blocks).
  using blocks =
      aba_blocks<A, S, T, !shared ? 1 : A::planar ? aba_block_links.planar : aba_block_links.spatial>;
  constexpr auto B = blocks::value;
  // The links of block U, first to last: their records and motions.
  const auto block_links = [&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int L0 = B.start[decltype(u)::value], R = B.len[decltype(u)::value];
    using W = typename blocks::template element<typename blocks::WS, L0 - 1>;
    using Mo = typename blocks::template element<typename blocks::MS, L0 - 1>;
    return [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
      return std::pair{std::array<W*, R>{&std::get<L0 - 1 + K>(ws)...},
                       std::array<const Mo*, R>{&std::get<L0 - 1 + K>(motions)...}};
    }(std::make_integer_sequence<int, R>{});
  };
  // Down the tree, parents first: each link's ω, c, p_A and own inertia
  // (aba_start). A link alone shares its step only in space: in a plane the
  // step is a few dozen instructions, less than its call costs (planar
  // 48-link chain: 2.1 µs unrolled, 2.2–2.3 shared; spatial 16 and 32 links
  // with the step shared: 7–15 % faster, tools/chain_counts.sh).
  constexpr bool shared_start = shared && !A::planar;
  constexpr auto F = load_flags<S>::value;
  constexpr auto K = inertia_kinds<S>::value;
  const auto parent_omega = [&](auto l) FLANGE_INLINE_LAMBDA {  // the World's is zero
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (LI::parent != 0) return std::get<LI::parent - 1>(ws).w;
    else return zero_vec<T>{};
  };
  const auto start_link = [&](auto l) FLANGE_INLINE_LAMBDA {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    auto& w = std::get<L - 1>(ws);
    const auto wP = parent_omega(l);
    const auto& I = scene.model().link[L];
    const auto& m = std::get<L - 1>(motions);
    if constexpr (shared_start)
      aba_start_shared<A, T, K.h_zero[L], K.I_kind[L], F.torque[L], F.force[L]>(w, m, wP, I, v + LI::v, n_ext[L],
                                                                               f_ext[L]);
    else aba_start<A, T, K.h_zero[L], K.I_kind[L], F.torque[L], F.force[L]>(w, m, wP, I, v + LI::v, n_ext[L], f_ext[L]);
  };
  for_units_split<S, B.n>([&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int L0 = B.start[decltype(u)::value], R = B.len[decltype(u)::value];
    if constexpr (R == 1) {
      start_link(std::integral_constant<int, L0>{});
    } else {
      using LI = link_info<S, L0>;
      const auto [wp, mp] = block_links(u);
      aba_start_block_shared<A, T, K.h_zero[L0], K.I_kind[L0], F.torque[L0], F.force[L0], R>(
          wp.data(), mp.data(), parent_omega(std::integral_constant<int, L0>{}), &scene.model().link[L0], v + LI::v,
          &n_ext[L0], &f_ext[L0]);
    }
  });
  // Up the tree, children first.
  constexpr bool jf = has_joint_forces<S>();
  // A joint that frees every direction (FreeMotion; a Planar joint in
  // planar algebra) passes its parent no articulated inertia, and of the
  // force only its own generalized force, S⁻ᵀ·τ. The general formula
  // reaches both only through cancellation (IA − U·D⁻¹·Uᵀ and
  // pA − U·D⁻¹·Sᵀ·pA), whose round-off is that of the heavy child and can
  // swamp a light parent (tests/hard_mass_ratio_test.cpp: masses from 1e-6
  // to 1e6 made a parent's articulated inertia negative).
  const auto frees_every_direction = [](auto l) constexpr {
    using LI = link_info<S, decltype(l)::value>;
    return LI::parent != 0 && LI::nv == algebra_size<A>;
  };
  // The record link l's step up adds its shares to: its parent's (none for a
  // root link or one that frees every direction).
  const auto parent_record = [&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (LI::parent != 0 && !frees_every_direction(l)) return &std::get<LI::parent - 1>(ws);
    else return static_cast<std::nullptr_t*>(nullptr);
  };
  // A failing pivot is a singular mass matrix at the rates of the joint (or
  // block) starting at link l (D is the joint's share of it once its subtree
  // is accounted for): reported as the mass-matrix path reports it, a
  // non-finite state included.
  const auto report = [&](auto l, const pivot_report<T>& piv) FLANGE_INLINE_LAMBDA {
    if (piv.index >= 0) [[unlikely]]
      singular_mass_matrix<S>(pivot_report<T>{link_info<S, decltype(l)::value>::v + piv.index, piv.d, piv.scale}, t,
                              q, v);
  };
  const auto up_link = [&](auto l) FLANGE_INLINE_LAMBDA {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    constexpr int nv = LI::nv;
    auto& w = std::get<L - 1>(ws);
    const auto& m = std::get<L - 1>(motions);
    constexpr bool frees_all = frees_every_direction(l);
    auto* parent = parent_record(l);
    if constexpr (shared) report(l, aba_up_shared<A, T, jf>(w, m, parent, tau.data() + LI::v));
    else report(l, aba_up<A, T, jf>(w, m, parent, tau.data() + LI::v));
    if constexpr (frees_all && has_generalized_force<typename LI::joint_type>) {
      Eigen::Matrix<T, nv, nv> St;
      [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
        ((St.row(K) = to_dense<A, T>(m.template col<K>().ang, m.template col<K>().lin).transpose()), ...);
      }(std::make_integer_sequence<int, nv>{});
      Eigen::Matrix<T, nv, 1> tj;
      for (int k = 0; k < nv; ++k) tj(k) = tau[LI::v + k];
      const auto pa = from_dense<A, T>(dvec<A, T>(St.partialPivLu().solve(tj)));
      auto& p = std::get<LI::parent - 1>(ws);
      const auto up = carry_up(m, force_pair{pa.ang, pa.lin});
      p.pA = as_force<A, T>(p.pA.n + up.n, p.pA.f + up.f);
    }
  };
  for_units_split<S, B.n, true>([&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int L0 = B.start[decltype(u)::value], R = B.len[decltype(u)::value];
    if constexpr (R == 1) {
      up_link(std::integral_constant<int, L0>{});
    } else {
      constexpr std::integral_constant<int, L0> first{};
      const auto [wp, mp] = block_links(u);
      report(first, aba_up_block_shared<A, T, jf, R>(wp.data(), mp.data(), parent_record(first),
                                                     tau.data() + link_info<S, L0>::v));
    }
  });
  // Down the tree, parents first: a' = X·a_P + c, v̇ = D⁻¹·(u − Uᵀ·a'), a = a' + S·v̇.
  const auto base = base_kinematics<A, T>(scene);
  const auto parent_acceleration = [&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (LI::parent != 0) return std::get<LI::parent - 1>(ws).a;
    else return motion_pair{base.wd, base.a};
  };
  for_units_split<S, B.n>([&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int L0 = B.start[decltype(u)::value], R = B.len[decltype(u)::value];
    using LI = link_info<S, L0>;
    constexpr bool has_children = children<S, L0 + R - 1>().size() > 0;
    const auto aP = parent_acceleration(std::integral_constant<int, L0>{});
    if constexpr (R == 1) {
      auto& w = std::get<L0 - 1>(ws);
      const auto& m = std::get<L0 - 1>(motions);
      if constexpr (shared) aba_down_shared<A, T, has_children>(w, m, aP, vdot + LI::v);
      else aba_down<A, T, has_children>(w, m, aP, vdot + LI::v);
    } else {
      const auto [wp, mp] = block_links(u);
      aba_down_block_shared<A, T, has_children, R>(wp.data(), mp.data(), aP, vdot + LI::v);
    }
  });
}

/// v̇ at (t, q, v) by the articulated-body algorithm, in the algebra the scene calls for.
template <aba_steps Steps = aba_steps::automatic, class S, class T>
void accelerations_articulated_body(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  accelerations_articulated_body_in<algebra_t<S>, Steps>(scene, t, q, v, vdot);
}

}  // namespace flange
