// 3 × 3 matrix products written out coefficient by coefficient, always
// inlined. Inside a scene's unrolled derivative, which is one large function,
// GCC declines to inline Eigen's product kernels: each 3 × 3 product became a
// call with its operands in memory (a planar articulated-body step spent
// 170 instructions per link in one such call for 27 multiplications). These
// are for the algorithms' inner steps; elsewhere Eigen's own are fine.
#pragma once
#include "flange/detail/inline.hpp"
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
/// a −= u·wᵀ
template <class T>
FLANGE_INLINE void sub_outer(Mat3<T>& a, const Vec3<T>& u, const Vec3<T>& w) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) -= u(i) * w(j);
}

}  // namespace flange::small
