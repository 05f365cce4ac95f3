// 3 × 3 matrix products written out coefficient by coefficient, always
// inlined. Inside a scene's unrolled derivative, which is one large function,
// GCC declines to inline Eigen's product kernels: each 3 × 3 product became a
// call with its operands in memory, several times the 27 multiplications'
// own cost. These
// are for the algorithms' inner steps; elsewhere Eigen's own are fine.
#pragma once
#include "flange/detail/inline.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/math/types.hpp"

namespace flange::small {

/// a·b
template <class T>
FLANGE_INLINE Mat3<T> mul(const Mat3<T>& a, const Mat3<T>& b) {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = a(i, 0) * b(0, j) + a(i, 1) * b(1, j) + a(i, 2) * b(2, j);
  return r;
}
/// aᵀ·b
template <class T>
FLANGE_INLINE Mat3<T> mul_tn(const Mat3<T>& a, const Mat3<T>& b) {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = a(0, i) * b(0, j) + a(1, i) * b(1, j) + a(2, i) * b(2, j);
  return r;
}
/// a·bᵀ
template <class T>
FLANGE_INLINE Mat3<T> mul_nt(const Mat3<T>& a, const Mat3<T>& b) {
  Mat3<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = a(i, 0) * b(j, 0) + a(i, 1) * b(j, 1) + a(i, 2) * b(j, 2);
  return r;
}
/// a·x
template <class T>
FLANGE_INLINE Vec3<T> mul(const Mat3<T>& a, const Vec3<T>& x) {
  return Vec3<T>(a(0, 0) * x(0) + a(0, 1) * x(1) + a(0, 2) * x(2), a(1, 0) * x(0) + a(1, 1) * x(1) + a(1, 2) * x(2),
                 a(2, 0) * x(0) + a(2, 1) * x(1) + a(2, 2) * x(2));
}
/// a += b, a −= b
template <class T>
FLANGE_INLINE void add_to(Mat3<T>& a, const Mat3<T>& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) += b(i, j);
}
template <class T>
FLANGE_INLINE void sub_from(Mat3<T>& a, const Mat3<T>& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) -= b(i, j);
}
/// a −= u·wᵀ, where the result is known to have row ZR and column ZC zero
/// (−1: none): those entries are set to zero, not computed.
template <int ZR = -1, int ZC = -1, class T>
FLANGE_INLINE void sub_outer(Mat3<T>& a, const Vec3<T>& u, const Vec3<T>& w) {
  detail::static_for<3>([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    detail::static_for<3>([&](auto j) FLANGE_INLINE_LAMBDA {
      constexpr int J = decltype(j)::value;
      if constexpr (I == ZR || J == ZC) a(I, J) = T(0);
      else a(I, J) -= u(I) * w(J);
    });
  });
}
/// f(i, j) for each entry of the upper triangle (i ≤ j), indices as constants.
template <class F>
FLANGE_INLINE void for_upper(F&& f) {
  detail::static_for<3>([&](auto i) FLANGE_INLINE_LAMBDA {
    constexpr int I = decltype(i)::value;
    detail::static_for<3>([&](auto j) FLANGE_INLINE_LAMBDA {
      constexpr int J = decltype(j)::value;
      if constexpr (J >= I) f(I, J);
    });
  });
}
/// a −= u·wᵀ where the sum of such terms keeps a symmetric (U·D⁻¹·Uᵀ):
/// the upper triangle, mirrored; row and column Z (−1: none), known to
/// become zero, are set to zero.
template <int Z = -1, class T>
FLANGE_INLINE void sub_outer_sym(Mat3<T>& a, const Vec3<T>& u, const Vec3<T>& w) {
  for_upper([&](int i, int j) FLANGE_INLINE_LAMBDA {
    if (i == Z || j == Z) a(j, i) = a(i, j) = T(0);
    else a(j, i) = a(i, j) -= u(i) * w(j);
  });
}
/// eᵀ·x·e for a symmetric x: x·e, then the upper triangle of eᵀ·(x·e), mirrored.
template <class T>
FLANGE_INLINE Mat3<T> congruence_sym(const Mat3<T>& e, const Mat3<T>& x) {
  const Mat3<T> a = mul(x, e);
  Mat3<T> r;
  for_upper([&](int i, int j) FLANGE_INLINE_LAMBDA {
    r(j, i) = r(i, j) = e(0, i) * a(0, j) + e(1, i) * a(1, j) + e(2, i) * a(2, j);
  });
  return r;
}
/// p̂·x (p̂ the cross-product matrix of p): each column of x crossed with p,
/// six products a column instead of nine.
template <class T>
FLANGE_INLINE Mat3<T> skew_mul(const Vec3<T>& p, const Mat3<T>& x) {
  Mat3<T> r;
  for (int j = 0; j < 3; ++j) {
    r(0, j) = p(1) * x(2, j) - p(2) * x(1, j);
    r(1, j) = p(2) * x(0, j) - p(0) * x(2, j);
    r(2, j) = p(0) * x(1, j) - p(1) * x(0, j);
  }
  return r;
}
/// a += b + p̂·hᵀ − g·p̂ where the result is known to be symmetric (the
/// shift of an articulated inertia's angular block): the upper triangle,
/// mirrored. (p̂·hᵀ)_ij = (p × h_j)_i and (g·p̂)_ij = (g_i × p)_j for rows h_j, g_i.
template <class T>
FLANGE_INLINE void add_shift_sym(Mat3<T>& a, const Mat3<T>& b, const Vec3<T>& p, const Mat3<T>& h, const Mat3<T>& g) {
  for_upper([&](int i, int j) FLANGE_INLINE_LAMBDA {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
    a(j, i) = a(i, j) += b(i, j) + (p(i1) * h(j, i2) - p(i2) * h(j, i1)) - (g(i, j1) * p(j2) - g(i, j2) * p(j1));
  });
}

}  // namespace flange::small
