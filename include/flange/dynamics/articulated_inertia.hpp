// The articulated-body inertia, and the dense forms of the algebra it works
// in: what the articulated-body algorithm (articulated_body.hpp) carries up
// the tree.
//
// In the algebras of algebra.hpp (6-D in space; ω_K and the plane's two
// directions in a plane), motions (α, a) and forces (n, f) at a link's origin
// in link coordinates. An articulated-body inertia I_A maps a link's
// acceleration to the force its subtree resists with; a joint's step turns
// it into I_a = I_A − U·D⁻¹·Uᵀ and carries it to the parent,
// Xᵀ·I_a·X (articulated_body.hpp).
#pragma once
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "flange/detail/inline.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/dynamics/algebra.hpp"
#include "flange/math/congruence.hpp"
#include "flange/math/read_alone.hpp"
#include "flange/math/rotation.hpp"
#include "flange/math/small_matrix.hpp"

namespace flange::detail {

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
/// computes their upper triangle and mirrors it. In a plane it is a symmetric 3 × 3 matrix
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
/// Only planar steps read their records alone (aba_up_step; blocks are planar,
/// costs.hpp aba_block_links): a spatial record is worked on in place.
template <int K, class T>
FLANGE_INLINE articulated_inertia<planar_algebra<K>, T> read_alone(const articulated_inertia<planar_algebra<K>, T>& a) {
  return {flange::read_alone(a.I)};
}
template <class N, class F>
FLANGE_INLINE force_pair<N, F> read_alone(const force_pair<N, F>& f) {
  return {flange::read_alone(f.n), flange::read_alone(f.f)};
}

}  // namespace flange::detail
