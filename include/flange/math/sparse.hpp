// 3-vectors, rotations and rotational inertias whose structure is a type.
//
// IEEE arithmetic forbids the compiler to drop a product with a zero it cannot
// prove exact (0·∞ is NaN), so a dense (0, 0, x) costs as much as any vector.
// The recursive algorithms therefore carry what is known about each quantity
// in its type, and these operations do only the arithmetic that is not zero:
//
//   svec<T, M>         a 3-vector whose components outside the bit mask M are
//                      zero (M = 0: the zero vector; M = 1 << i: along axis i;
//                      M = 7: dense)
//   identity_rotation, coordinate_rotation<T, I>, Mat3<T>
//                      coordinate transforms: none, about coordinate axis I
//                      (the paper's R_rel with n = e_I), and any
//   zero_inertia, diag_inertia<T, M>, Mat3<T>
//                      rotational inertias: none, diagonal (entries in M),
//                      and any (symmetric)
//   szero              a scalar known to be zero
//
// A result's type follows from its operands' types: rotating a vector along
// the axis of a coordinate_rotation leaves it along that axis, the cross product of
// two vectors along one axis is the zero vector, and so on. A link behind only
// prismatic joints thus has ω of type svec<T, 0>, and every product with it is
// never generated. The same rules serve planar scenes, whose quantities are
// projected onto the plane first (dynamics/algebra.hpp): ω along the normal,
// offsets and forces in the plane.
#pragma once
#include <type_traits>

#include "flange/detail/inline.hpp"
#include "flange/math/rotation.hpp"
#include "flange/math/types.hpp"

namespace flange {

// ------------------------------------------------------------ scalars

/// A scalar known to be zero.
struct szero {};

template <class A>
inline constexpr bool is_szero = std::is_same_v<std::remove_cvref_t<A>, szero>;

FLANGE_INLINE constexpr szero operator+(szero, szero) { return {}; }
FLANGE_INLINE constexpr szero operator-(szero, szero) { return {}; }
FLANGE_INLINE constexpr szero operator-(szero) { return {}; }
template <class T>
  requires(!is_szero<T>)
FLANGE_INLINE constexpr T operator+(const T& a, szero) { return a; }
template <class T>
  requires(!is_szero<T>)
FLANGE_INLINE constexpr T operator+(szero, const T& b) { return b; }
template <class T>
  requires(!is_szero<T>)
FLANGE_INLINE constexpr T operator-(const T& a, szero) { return a; }
template <class T>
  requires(!is_szero<T>)
FLANGE_INLINE constexpr T operator-(szero, const T& b) { return -b; }

/// A scalar value, with a zero of type szero becoming T(0).
template <class T, class A>
FLANGE_INLINE constexpr T value_of(const A& a) {
  if constexpr (is_szero<A>) return T(0);
  else return a;
}

// ------------------------------------------------------------ vectors

namespace detail {
constexpr bool bit(int m, int i) { return (m >> i) & 1; }
constexpr int popcount3(int m) { return bit(m, 0) + bit(m, 1) + bit(m, 2); }
/// Where component i of a vector with mask m is stored.
constexpr int slot(int m, int i) {
  int k = 0;
  for (int j = 0; j < i; ++j) k += bit(m, j);
  return k;
}
}  // namespace detail

/// A 3-vector whose components outside the bit mask M are zero. Only the
/// components in M are stored (packed), so copying it moves nothing else.
template <class T, int M>
struct svec {
  static_assert(M >= 0 && M <= 7);
  static constexpr int mask = M;
  using scalar = T;
  static constexpr bool has(int i) { return (M >> i) & 1; }
  T c_[detail::popcount3(M)];

  /// Component I, which the mask must hold.
  template <int I>
  FLANGE_INLINE T& at() {
    static_assert(has(I), "flange: this component is known to be zero");
    return c_[detail::slot(M, I)];
  }
  template <int I>
  FLANGE_INLINE const T& at() const {
    static_assert(has(I), "flange: this component is known to be zero");
    return c_[detail::slot(M, I)];
  }
  /// Component I (a constant zero outside the mask).
  template <int I>
  [[nodiscard]] FLANGE_INLINE T get() const {
    if constexpr (has(I)) return at<I>();
    else return T(0);
  }
  /// The dense vector.
  [[nodiscard]] FLANGE_INLINE Vec3<T> dense() const { return Vec3<T>(get<0>(), get<1>(), get<2>()); }
};
template <class T>
struct svec<T, 0> {
  static constexpr int mask = 0;
  using scalar = T;
  static constexpr bool has(int) { return false; }
  /// Never called: declared so that a compiler that looks member names up
  /// early (clang) finds it in code a mask rules out.
  template <int I>
  T& at();
  template <int I>
  const T& at() const;
  template <int I>
  [[nodiscard]] FLANGE_INLINE T get() const {
    return T(0);
  }
  [[nodiscard]] FLANGE_INLINE Vec3<T> dense() const { return zeros<Vec3<T>>(); }
};

template <class V>
inline constexpr bool is_svec = false;
template <class T, int M>
inline constexpr bool is_svec<svec<T, M>> = true;

template <class V>
inline constexpr bool is_zero_vec = std::remove_cvref_t<V>::mask == 0;

template <class T>
using zero_vec = svec<T, 0>;
/// x·e_I.
template <class T, int I>
using axial_vec = svec<T, 1 << I>;
template <class T>
using dense_vec = svec<T, 7>;

namespace detail {
/// f(integral_constant<i>) for i = 0, 1, 2: component loops unrolled at compile
/// time, so that a component outside a mask is never even named.
template <class F>
FLANGE_INLINE constexpr void for3(F&& f) {
  f(std::integral_constant<int, 0>{});
  f(std::integral_constant<int, 1>{});
  f(std::integral_constant<int, 2>{});
}
}  // namespace detail

template <class T, int I>
FLANGE_INLINE constexpr axial_vec<T, I> axial(const T& x) {
  axial_vec<T, I> r;
  r.template at<I>() = x;
  return r;
}
/// A dense Eigen vector as an svec, keeping only the components in M (the
/// caller knows the others are zero, or that they do not matter).
template <int M = 7, class D>
FLANGE_INLINE auto to_svec(const Eigen::MatrixBase<D>& v) {
  using T = typename D::Scalar;
  svec<T, M> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (detail::bit(M, I)) r.template at<I>() = v(I);
  });
  return r;
}
/// v with only its components in M kept.
template <int M, class T, int N>
FLANGE_INLINE svec<T, M & N> restrict_to(const svec<T, N>& v) {
  svec<T, M & N> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (detail::bit(M & N, I)) r.template at<I>() = v.template at<I>();
  });
  return r;
}

/// v with the wider mask M: its own components copied, the others zero.
/// (Not svec<T, M>{} + v: that adds 0.0 to each of v's components, an
/// addition the compiler must keep, since −0.0 + 0.0 is +0.0.)
template <int M, class T, int N>
FLANGE_INLINE svec<T, M> widen_to(const svec<T, N>& v) {
  static_assert((M & N) == N, "flange: widen_to would drop a component");
  svec<T, M> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (detail::bit(M, I)) r.template at<I>() = v.template get<I>();
  });
  return r;
}

template <class T, int A, int B>
FLANGE_INLINE svec<T, A | B> operator+(const svec<T, A>& a, const svec<T, B>& b) {
  svec<T, A | B> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    constexpr bool x = detail::bit(A, I), y = detail::bit(B, I);
    if constexpr (x && y) r.template at<I>() = a.template at<I>() + b.template at<I>();
    else if constexpr (x) r.template at<I>() = a.template at<I>();
    else if constexpr (y) r.template at<I>() = b.template at<I>();
  });
  return r;
}
template <class T, int A>
FLANGE_INLINE svec<T, A> operator-(const svec<T, A>& a) {
  svec<T, A> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (detail::bit(A, I)) r.template at<I>() = -a.template at<I>();
  });
  return r;
}
template <class T, int A, int B>
FLANGE_INLINE svec<T, A | B> operator-(const svec<T, A>& a, const svec<T, B>& b) {
  svec<T, A | B> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    constexpr bool x = detail::bit(A, I), y = detail::bit(B, I);
    if constexpr (x && y) r.template at<I>() = a.template at<I>() - b.template at<I>();
    else if constexpr (x) r.template at<I>() = a.template at<I>();
    else if constexpr (y) r.template at<I>() = -b.template at<I>();
  });
  return r;
}
/// s·a.
template <class T, int A>
FLANGE_INLINE svec<T, A> operator*(const T& s, const svec<T, A>& a) {
  svec<T, A> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    if constexpr (detail::bit(A, I)) r.template at<I>() = s * a.template at<I>();
  });
  return r;
}
template <class T, int A>
FLANGE_INLINE zero_vec<T> operator*(szero, const svec<T, A>&) {
  return {};
}

namespace detail {
/// The mask of a × b: component i is a_j·b_k − a_k·b_j for (i, j, k) cyclic.
constexpr int cross_mask(int a, int b) {
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if ((bit(a, j) && bit(b, k)) || (bit(a, k) && bit(b, j))) m |= 1 << i;
  }
  return m;
}
}  // namespace detail

template <class T, int A, int B>
FLANGE_INLINE svec<T, detail::cross_mask(A, B)> cross(const svec<T, A>& a, const svec<T, B>& b) {
  constexpr int R = detail::cross_mask(A, B);
  svec<T, R> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value, J = (I + 1) % 3, K = (I + 2) % 3;
    constexpr bool p = detail::bit(A, J) && detail::bit(B, K), n = detail::bit(A, K) && detail::bit(B, J);
    if constexpr (p && n) r.template at<I>() = a.template at<J>() * b.template at<K>() - a.template at<K>() * b.template at<J>();
    else if constexpr (p) r.template at<I>() = a.template at<J>() * b.template at<K>();
    else if constexpr (n) r.template at<I>() = -(a.template at<K>() * b.template at<J>());
  });
  return r;
}

/// w × (w × p), the centripetal term. For w along one axis K and p normal to
/// it this is −w_K²·p: one product fewer per component than the two cross
/// products (every link of a planar scene).
template <class T, int A, int B>
FLANGE_INLINE auto double_cross(const svec<T, A>& w, const svec<T, B>& p) {
  if constexpr ((A == 1 || A == 2 || A == 4) && (A & B) == 0) {
    constexpr int K = A == 1 ? 0 : A == 2 ? 1 : 2;
    return (-(w.template at<K>() * w.template at<K>())) * p;
  } else {
    return cross(w, cross(w, p));
  }
}

/// a·b, szero when no component is shared.
template <class T, int A, int B>
FLANGE_INLINE auto dot(const svec<T, A>& a, const svec<T, B>& b) {
  constexpr int C = A & B;
  if constexpr (C == 0) {
    return szero{};
  } else {
    constexpr int first = detail::bit(C, 0) ? 0 : detail::bit(C, 1) ? 1 : 2;
    T s = a.template at<first>() * b.template at<first>();
    detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
      constexpr int I = decltype(i)::value;
      if constexpr (I > first && detail::bit(C, I)) s += a.template at<I>() * b.template at<I>();
    });
    return s;
  }
}

// ------------------------------------------------------------ rotations

/// No rotation.
struct identity_rotation {};

/// The rotation about coordinate axis I in the paper's convention (R_rel with
/// n = e_I, angle φ): (E·v)_I = v_I, (E·v)_j = c·v_j + s·v_k,
/// (E·v)_k = −s·v_j + c·v_k with (I, j, k) cyclic, c = cos φ, s = sin φ.
template <class T, int I>
struct coordinate_rotation {
  static constexpr int axis = I, j = (I + 1) % 3, k = (I + 2) % 3;
  T c, s;
};

template <class E>
inline constexpr bool is_identity_rotation = std::is_same_v<std::remove_cvref_t<E>, identity_rotation>;

/// A·B of two coordinate rotations about different axes: first B, then A,
/// each applied as its (c, s) pair (4 products a vector against a 3 × 3
/// matrix's 9 in all). An axis frame's E = R_z(q)·R_x(α) is one
/// (dynamics/axis_frames.hpp).
template <class A, class B>
struct rotation_product {
  A a;
  B b;
};
template <class E>
inline constexpr bool is_rotation_product = false;
template <class A, class B>
inline constexpr bool is_rotation_product<rotation_product<A, B>> = true;

namespace detail {
/// Components a rotation about axis I fills from mask M.
constexpr int axis_rotation_mask(int I, int M) {
  const int j = (I + 1) % 3, k = (I + 2) % 3;
  int r = M & (1 << I);
  if ((M >> j & 1) || (M >> k & 1)) r |= (1 << j) | (1 << k);
  return r;
}

/// A rotation about axis I by (c, σ·s), σ = ±1: E·v for σ = 1, Eᵀ·v for
/// σ = −1. σ picks between a sum and a difference instead of negating s,
/// which would cost an instruction per rotation (c·a − s·b and c·a + (−s)·b
/// are the same number in IEEE arithmetic).
template <int Sigma, class T, int I, int M>
FLANGE_INLINE svec<T, axis_rotation_mask(I, M)> axis_rot(const coordinate_rotation<T, I>& E, const svec<T, M>& v) {
  constexpr int j = (I + 1) % 3, k = (I + 2) % 3;
  svec<T, axis_rotation_mask(I, M)> r;
  if constexpr (bit(M, I)) r.template at<I>() = v.template at<I>();
  constexpr bool hj = bit(M, j), hk = bit(M, k);
  const T &c = E.c, &s = E.s;
  if constexpr (hj && hk) {
    const T &a = v.template at<j>(), &b = v.template at<k>();
    if constexpr (Sigma > 0) {
      r.template at<j>() = c * a + s * b;
      r.template at<k>() = c * b - s * a;
    } else {
      r.template at<j>() = c * a - s * b;
      r.template at<k>() = s * a + c * b;
    }
  } else if constexpr (hj) {
    r.template at<j>() = c * v.template at<j>();
    r.template at<k>() = Sigma > 0 ? -(s * v.template at<j>()) : s * v.template at<j>();
  } else if constexpr (hk) {
    r.template at<j>() = Sigma > 0 ? s * v.template at<k>() : -(s * v.template at<k>());
    r.template at<k>() = c * v.template at<k>();
  }
  return r;
}
}  // namespace detail

/// E·v (parent coordinates into child coordinates).
template <class T, int M>
FLANGE_INLINE svec<T, M> rot(identity_rotation, const svec<T, M>& v) {
  return v;
}
template <class T, int I, int M>
FLANGE_INLINE svec<T, detail::axis_rotation_mask(I, M)> rot(const coordinate_rotation<T, I>& E, const svec<T, M>& v) {
  return detail::axis_rot<1>(E, v);
}
/// Rows (Transposed: columns) of a dense matrix times the components of v in M.
template <bool Transposed, class T, int M>
FLANGE_INLINE svec<T, (M == 0 ? 0 : 7)> dense_times(const Mat3<T>& E, const svec<T, M>& v) {
  svec<T, (M == 0 ? 0 : 7)> r;
  if constexpr (M != 0) {
    constexpr int first = detail::bit(M, 0) ? 0 : detail::bit(M, 1) ? 1 : 2;
    detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
      constexpr int I = decltype(i)::value;
      auto e = [&](int row, int col) FLANGE_INLINE_LAMBDA { return Transposed ? E(col, row) : E(row, col); };
      T x = e(I, first) * v.template at<first>();
      detail::for3([&](auto k) FLANGE_INLINE_LAMBDA {
        constexpr int K = decltype(k)::value;
        if constexpr (K > first && detail::bit(M, K)) x += e(I, K) * v.template at<K>();
      });
      r.template at<I>() = x;
    });
  }
  return r;
}
template <class T, int M>
FLANGE_INLINE svec<T, (M == 0 ? 0 : 7)> rot(const Mat3<T>& E, const svec<T, M>& v) {
  return dense_times<false>(E, v);
}
template <class A, class B, class T, int M>
FLANGE_INLINE auto rot(const rotation_product<A, B>& E, const svec<T, M>& v) {
  return rot(E.a, rot(E.b, v));
}
/// Eᵀ·v (child coordinates back into parent coordinates).
template <class T, int M>
FLANGE_INLINE svec<T, M> rot_t(identity_rotation, const svec<T, M>& v) {
  return v;
}
template <class T, int I, int M>
FLANGE_INLINE svec<T, detail::axis_rotation_mask(I, M)> rot_t(const coordinate_rotation<T, I>& E, const svec<T, M>& v) {
  return detail::axis_rot<-1>(E, v);
}
template <class T, int M>
FLANGE_INLINE svec<T, (M == 0 ? 0 : 7)> rot_t(const Mat3<T>& E, const svec<T, M>& v) {
  return dense_times<true>(E, v);
}
template <class A, class B, class T, int M>
FLANGE_INLINE auto rot_t(const rotation_product<A, B>& E, const svec<T, M>& v) {
  return rot_t(E.b, rot_t(E.a, v));
}
/// The 3 × 3 matrix of a typed rotation E (x_child = E·x_parent), in scalar T.
template <class T, class E>
Mat3<T> dense_rotation(const E& e) {
  Mat3<T> R;
  for (int k = 0; k < 3; ++k) R.col(k) = rot(e, to_svec(Vec3<T>(Vec3<T>::Unit(k)))).dense();
  return R;
}

/// The rotation as a dense matrix.
template <class T>
FLANGE_INLINE Mat3<T> to_matrix(identity_rotation) {
  return Mat3<T>::Identity();
}
template <class T, int I>
FLANGE_INLINE Mat3<T> to_matrix(const coordinate_rotation<T, I>& E) {
  constexpr int j = (I + 1) % 3, k = (I + 2) % 3;
  Mat3<T> m = Mat3<T>::Zero();
  m(I, I) = T(1);
  m(j, j) = E.c;
  m(j, k) = E.s;
  m(k, j) = -E.s;
  m(k, k) = E.c;
  return m;
}
template <class T>
FLANGE_INLINE const Mat3<T>& to_matrix(const Mat3<T>& E) {
  return E;
}
template <class T, class A, class B>
FLANGE_INLINE Mat3<T> to_matrix(const rotation_product<A, B>& E) {
  return to_matrix<T>(E.a) * to_matrix<T>(E.b);
}

namespace detail {
template <class E>
struct rotation_scalar;
template <class T, int I>
struct rotation_scalar<coordinate_rotation<T, I>> {
  using type = T;
};
template <class T>
struct rotation_scalar<Eigen::Matrix<T, 3, 3>> {
  using type = T;
};
template <class A, class B>
struct rotation_scalar<rotation_product<A, B>> {
  using type = typename rotation_scalar<A>::type;
};
template <class A, class B>
inline constexpr bool same_axis_rotation = false;
template <class A>
inline constexpr bool is_coordinate_rotation = false;
template <class T, int I>
inline constexpr bool is_coordinate_rotation<coordinate_rotation<T, I>> = true;
template <class A>
inline constexpr bool is_dense_rotation = false;
template <class T>
inline constexpr bool is_dense_rotation<Eigen::Matrix<T, 3, 3>> = true;
template <class T, int I>
inline constexpr bool same_axis_rotation<coordinate_rotation<T, I>, coordinate_rotation<T, I>> = true;
}  // namespace detail

/// A·B: first B, then A (each rotates parent into child coordinates).
template <class A, class B>
FLANGE_INLINE auto compose(const A& a, const B& b) {
  if constexpr (is_identity_rotation<A> && is_identity_rotation<B>) {
    return identity_rotation{};
  } else if constexpr (is_identity_rotation<B>) {
    return a;
  } else if constexpr (is_identity_rotation<A>) {
    return b;
  } else if constexpr (detail::same_axis_rotation<A, B>) {
    return A{a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s};
  } else if constexpr (detail::is_coordinate_rotation<A> && detail::is_coordinate_rotation<B>) {
    return rotation_product<A, B>{a, b};
  } else if constexpr (detail::is_coordinate_rotation<A> && detail::is_dense_rotation<B>) {
    // A turns rows j and k of B and keeps row I: 12 products, not 27.
    using T = typename detail::rotation_scalar<A>::type;
    constexpr int I = A::axis, j = A::j, k = A::k;
    Mat3<T> r;
    for (int col = 0; col < 3; ++col) {
      r(I, col) = b(I, col);
      r(j, col) = a.c * b(j, col) + a.s * b(k, col);
      r(k, col) = a.c * b(k, col) - a.s * b(j, col);
    }
    return r;
  } else {
    using T = typename detail::rotation_scalar<A>::type;
    return Mat3<T>(to_matrix<T>(a) * to_matrix<T>(b));
  }
}

/// The transpose (inverse) of a rotation.
FLANGE_INLINE identity_rotation transpose(identity_rotation) { return {}; }
template <class T, int I>
FLANGE_INLINE coordinate_rotation<T, I> transpose(const coordinate_rotation<T, I>& E) {
  return {E.c, -E.s};
}
template <class T>
FLANGE_INLINE Mat3<T> transpose(const Mat3<T>& E) {
  return E.transpose();
}
template <class A, class B>
FLANGE_INLINE auto transpose(const rotation_product<A, B>& E) {
  return rotation_product<decltype(transpose(E.b)), decltype(transpose(E.a))>{transpose(E.b), transpose(E.a)};
}

// ------------------------------------------------------------ rotational inertias

/// No rotational inertia.
struct zero_inertia {};
/// A diagonal rotational inertia; entries outside M are zero, or (in a
/// projected algebra) not tracked.
template <class T, int M>
struct diag_inertia {
  static constexpr int mask = M;
  T d[3];
};
// A dense symmetric inertia is a Mat3<T>.

template <class I>
inline constexpr bool is_zero_inertia = std::is_same_v<std::remove_cvref_t<I>, zero_inertia>;

template <class T, int M>
FLANGE_INLINE zero_vec<T> operator*(zero_inertia, const svec<T, M>&) {
  return {};
}
template <class T, int D, int M>
FLANGE_INLINE svec<T, D & M> operator*(const diag_inertia<T, D>& I, const svec<T, M>& v) {
  svec<T, D & M> r;
  detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int K = decltype(i)::value;
    if constexpr (detail::bit(D & M, K)) r.template at<K>() = I.d[K] * v.template at<K>();
  });
  return r;
}
template <class T, int M>
FLANGE_INLINE svec<T, (M == 0 ? 0 : 7)> operator*(const Mat3<T>& I, const svec<T, M>& v) {
  return rot(I, v);  // the same product
}

FLANGE_INLINE szero trace(zero_inertia) { return {}; }
template <class T, int D>
FLANGE_INLINE auto trace(const diag_inertia<T, D>& I) {
  if constexpr (D == 0) {
    return szero{};
  } else {
    constexpr int first = detail::bit(D, 0) ? 0 : detail::bit(D, 1) ? 1 : 2;
    T s = I.d[first];
    detail::for3([&](auto i) FLANGE_INLINE_LAMBDA {
      constexpr int K = decltype(i)::value;
      if constexpr (K > first && detail::bit(D, K)) s += I.d[K];
    });
    return s;
  }
}
template <class T>
FLANGE_INLINE T trace(const Mat3<T>& I) {
  return I(0, 0) + I(1, 1) + I(2, 2);  // Eigen's trace(), without its reduction machinery to compile
}

/// The inertia as a dense matrix.
template <class T>
FLANGE_INLINE Mat3<T> to_matrix(zero_inertia) {
  return Mat3<T>::Zero();
}
template <class T, int D>
FLANGE_INLINE Mat3<T> to_matrix(const diag_inertia<T, D>& I) {
  Mat3<T> m = Mat3<T>::Zero();
  for (int i = 0; i < 3; ++i)
    if ((D >> i) & 1) m(i, i) = I.d[i];
  return m;
}

}  // namespace flange
