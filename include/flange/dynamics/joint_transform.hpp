// The motion a joint allows, as the recursive algorithms need it.
//
// For the link behind a joint, E rotates parent-link coordinates into child
// coordinates and p is the child origin seen from the joint's parent-side
// frame (parent coordinates). A joint may sit in the tree either way round:
// Dir = +1 when frame_a faces the World, −1 when frame_b does. Reversing a
// revolute joint is the same as turning its axis round (R_rel(φ)' = R_rel(−φ)),
// so the algorithms only ever see the signed axis σ·n.
//
// An axis known at compile time (axis::x/y/z) gives 2-D rotation arithmetic:
// (E·v)_i = v_i, (E·v)_j = c·v_j + s·v_k, (E·v)_k = −s·v_j + c·v_k with
// (i, j, k) cyclic, which is the paper's R_rel with n = e_i.
#pragma once
#include <cmath>

#include "flange/joints/prismatic.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/math/axial.hpp"
#include "flange/math/rotation.hpp"

namespace flange::detail {

template <class J, int Dir, class T, bool Revolute = (J::type == joint_type::revolute), bool Fixed = J::axis_type::fixed>
struct joint_transform;

/// Revolute joint about a coordinate axis.
template <class J, int Dir, class T>
struct joint_transform<J, Dir, T, true, true> {
  static constexpr bool rotates = true, translates = false;
  static constexpr int i = J::axis_type::index, j = (i + 1) % 3, k = (i + 2) % 3;
  T c, s;
  joint_transform(const J&, const T& q) {
    using std::cos;
    using std::sin;
    c = cos(q);
    s = Dir * sin(q);
  }
  [[nodiscard]] Vec3<T> rot(const Vec3<T>& v) const {
    Vec3<T> r;
    r(i) = v(i);
    r(j) = c * v(j) + s * v(k);
    r(k) = -s * v(j) + c * v(k);
    return r;
  }
  [[nodiscard]] Vec3<T> rot_t(const Vec3<T>& v) const {
    Vec3<T> r;
    r(i) = v(i);
    r(j) = c * v(j) - s * v(k);
    r(k) = s * v(j) + c * v(k);
    return r;
  }
  [[nodiscard]] Vec3<T> axis(const T& x) const {
    Vec3<T> r = Vec3<T>::Zero();
    r(i) = Dir * x;
    return r;
  }
  [[nodiscard]] T axis_dot(const Vec3<T>& v) const { return Dir * v(i); }
  /// The signed unit axis σ·n, axial: multiplications by its zeros are skipped.
  [[nodiscard]] axial<T, i> unit() const { return {T(Dir)}; }
  /// ω × (σ·n·x) without the multiplications by zero.
  [[nodiscard]] Vec3<T> cross_axis(const Vec3<T>& w, const T& x) const {
    Vec3<T> r;
    r(i) = T(0);
    r(j) = w(k) * (Dir * x);
    r(k) = -w(j) * (Dir * x);
    return r;
  }
  [[nodiscard]] Mat3<T> matrix() const {
    Mat3<T> m = Mat3<T>::Zero();
    m(i, i) = T(1);
    m(j, j) = c;
    m(j, k) = s;
    m(k, j) = -s;
    m(k, k) = c;
    return m;
  }
  [[nodiscard]] Vec3<T> p() const { return Vec3<T>::Zero(); }
};

/// Revolute joint about a run-time axis.
template <class J, int Dir, class T>
struct joint_transform<J, Dir, T, true, false> {
  static constexpr bool rotates = true, translates = false;
  Vec3<T> n;
  Mat3<T> E;
  joint_transform(const J& joint, const T& q) : n(T(Dir) * joint.n().template cast<T>()), E(axis_rotation<T>(n, q)) {}
  [[nodiscard]] Vec3<T> rot(const Vec3<T>& v) const { return E * v; }
  [[nodiscard]] Vec3<T> rot_t(const Vec3<T>& v) const { return E.transpose() * v; }
  [[nodiscard]] Vec3<T> axis(const T& x) const { return n * x; }
  [[nodiscard]] T axis_dot(const Vec3<T>& v) const { return n.dot(v); }
  [[nodiscard]] const Vec3<T>& unit() const { return n; }
  [[nodiscard]] Vec3<T> cross_axis(const Vec3<T>& w, const T& x) const { return w.cross(n * x); }
  [[nodiscard]] const Mat3<T>& matrix() const { return E; }
  [[nodiscard]] Vec3<T> p() const { return Vec3<T>::Zero(); }
};

/// Prismatic joint: no rotation; the child origin moves by σ·s·n.
template <class J, int Dir, class T, bool Fixed>
struct joint_transform<J, Dir, T, false, Fixed> {
  static constexpr bool rotates = false, translates = true;
  Vec3<T> n;
  T q;
  joint_transform(const J& joint, const T& s) : n(T(Dir) * joint.n().template cast<T>()), q(s) {}
  [[nodiscard]] Vec3<T> rot(const Vec3<T>& v) const { return v; }
  [[nodiscard]] Vec3<T> rot_t(const Vec3<T>& v) const { return v; }
  [[nodiscard]] Vec3<T> axis(const T& x) const { return n * x; }
  [[nodiscard]] T axis_dot(const Vec3<T>& v) const { return n.dot(v); }
  [[nodiscard]] const Vec3<T>& unit() const { return n; }
  [[nodiscard]] Vec3<T> cross_axis(const Vec3<T>& w, const T& x) const { return w.cross(n * x); }
  [[nodiscard]] Mat3<T> matrix() const { return Mat3<T>::Identity(); }
  [[nodiscard]] Vec3<T> p() const { return n * q; }
};

}  // namespace flange::detail
