// A vector known, at compile time, to lie along coordinate axis I: x·e_I.
//
// IEEE arithmetic forbids the compiler to drop a multiplication by a zero it
// cannot see is exact (0·∞ is NaN), so a dense (0, 0, x) costs as much as any
// vector. Angular velocities of links behind joints with parallel coordinate
// axes (every planar scene) are axial; the recursive algorithms keep them in
// this form, and these overloads do only the arithmetic that is not zero.
#pragma once
#include "flange/math/types.hpp"

namespace flange {

template <class T, int I>
struct axial {
  static constexpr int j = (I + 1) % 3, k = (I + 2) % 3;
  T x;
};

template <class T>
const Vec3<T>& dense(const Vec3<T>& v) {
  return v;
}
template <class T, int I>
Vec3<T> dense(const axial<T, I>& a) {
  Vec3<T> r = Vec3<T>::Zero();
  r(I) = a.x;
  return r;
}

template <class T>
Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return a.cross(b);
}
/// (x·e_I) × b
template <class T, int I>
Vec3<T> cross(const axial<T, I>& a, const Vec3<T>& b) {
  Vec3<T> r;
  r(I) = T(0);
  r(axial<T, I>::j) = -a.x * b(axial<T, I>::k);
  r(axial<T, I>::k) = a.x * b(axial<T, I>::j);
  return r;
}
template <class T, int I>
Vec3<T> cross(const Vec3<T>& a, const axial<T, I>& b) {
  Vec3<T> r;
  r(I) = T(0);
  r(axial<T, I>::j) = a(axial<T, I>::k) * b.x;
  r(axial<T, I>::k) = -a(axial<T, I>::j) * b.x;
  return r;
}

template <class T, class M>
Vec3<T> mul(const M& m, const Vec3<T>& v) {
  return m * v;
}
/// M·(x·e_I): one column.
template <class T, int I, class M>
Vec3<T> mul(const M& m, const axial<T, I>& a) {
  return m.col(I) * a.x;
}

}  // namespace flange
