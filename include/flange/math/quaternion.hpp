// Unit quaternions for orientations, in the paper's conventions.
//
//   Q = (x, y, z, w) = (n·sin(θ/2), cos(θ/2)): vector part first, scalar
//   last, as Modelica's Frames.Quaternions and Eigen's coefficient order.
//   Q describes frame_b as frame_a turned by θ about n. Its rotation matrix
//   in the paper's convention rotates frame_a coordinates into frame_b's:
//
//     R(Q) = n·n' + (1 − n·n')·cos θ − ñ·sin θ  (= axis_rotation(n, θ))
//
//   written homogeneously (every entry quadratic in Q, divided by |Q|²), so
//   R is orthogonal to round-off for any non-zero Q: an integrator's drift of
//   |Q| away from 1 never makes R non-orthogonal.
//
//   With ω the angular velocity of frame_b relative to frame_a, in frame_b
//   coordinates (ω̃ = R·Ṙ'):  Q̇ = ½·Q ⊗ (ω, 0) = ½·(w·ω + v × ω, −v·ω).
//   This keeps |Q| constant in exact arithmetic; numerically |Q| drifts at
//   the integrator's error level, and normalize() projects it back.
#pragma once
#include <cmath>

#include "flange/detail/inline.hpp"
#include "flange/math/rotation.hpp"
#include "flange/math/types.hpp"

namespace flange::quaternion {

/// R(Q) in the paper's convention, for Q = q[0..3] = (x, y, z, w), any norm.
template <class T>
FLANGE_INLINE Mat3<T> to_rotation(const T* q) {
  const T x = q[0], y = q[1], z = q[2], w = q[3];
  const T xx = x * x, yy = y * y, zz = z * z, ww = w * w;
  const T inv = T(1) / (xx + yy + zz + ww);
  const T xy = x * y, xz = x * z, yz = y * z, wx = w * x, wy = w * y, wz = w * z;
  Mat3<T> R;  // the transpose of the active rotation matrix
  R(0, 0) = (ww + xx - yy - zz) * inv, R(0, 1) = T(2) * (xy + wz) * inv, R(0, 2) = T(2) * (xz - wy) * inv;
  R(1, 0) = T(2) * (xy - wz) * inv, R(1, 1) = (ww - xx + yy - zz) * inv, R(1, 2) = T(2) * (yz + wx) * inv;
  R(2, 0) = T(2) * (xz + wy) * inv, R(2, 1) = T(2) * (yz - wx) * inv, R(2, 2) = (ww - xx - yy + zz) * inv;
  return R;
}

/// Q̇ = ½·Q ⊗ (ω, 0), ω in frame_b coordinates.
template <class T>
FLANGE_INLINE void rate(const T* q, const T* w, T* qd) {
  const T x = q[0], y = q[1], z = q[2], s = q[3];
  qd[0] = T(0.5) * (s * w[0] + y * w[2] - z * w[1]);
  qd[1] = T(0.5) * (s * w[1] + z * w[0] - x * w[2]);
  qd[2] = T(0.5) * (s * w[2] + x * w[1] - y * w[0]);
  qd[3] = T(-0.5) * (x * w[0] + y * w[1] + z * w[2]);
}

/// The unit quaternion of a rotation matrix R (paper convention), by
/// Shepperd's method: the largest of the four squared components is taken
/// first, so no division is by a small number. w ≥ 0.
template <class T>
void from_rotation(const Mat3<T>& R, T* q) {
  using std::sqrt;
  // A = Rᵀ is the active rotation; its trace and diagonal give 4·x², … .
  const T a00 = R(0, 0), a11 = R(1, 1), a22 = R(2, 2);
  const T a21 = R(1, 2), a12 = R(2, 1), a02 = R(2, 0), a20 = R(0, 2), a10 = R(0, 1), a01 = R(1, 0);
  const T tr = a00 + a11 + a22;
  T x, y, z, w;
  if (tr >= a00 && tr >= a11 && tr >= a22) {
    w = sqrt(T(1) + tr) / T(2);
    x = (a21 - a12) / (T(4) * w);
    y = (a02 - a20) / (T(4) * w);
    z = (a10 - a01) / (T(4) * w);
  } else if (a00 >= a11 && a00 >= a22) {
    x = sqrt(T(1) + a00 - a11 - a22) / T(2);
    w = (a21 - a12) / (T(4) * x);
    y = (a01 + a10) / (T(4) * x);
    z = (a02 + a20) / (T(4) * x);
  } else if (a11 >= a22) {
    y = sqrt(T(1) - a00 + a11 - a22) / T(2);
    w = (a02 - a20) / (T(4) * y);
    x = (a01 + a10) / (T(4) * y);
    z = (a12 + a21) / (T(4) * y);
  } else {
    z = sqrt(T(1) - a00 - a11 + a22) / T(2);
    w = (a10 - a01) / (T(4) * z);
    x = (a02 + a20) / (T(4) * z);
    y = (a12 + a21) / (T(4) * z);
  }
  if (w < T(0)) x = -x, y = -y, z = -z, w = -w;
  q[0] = x, q[1] = y, q[2] = z, q[3] = w;
}

/// Q scaled to unit norm.
template <class T>
void normalize(T* q) {
  using std::sqrt;
  const T n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int i = 0; i < 4; ++i) q[i] /= n;
}

}  // namespace flange::quaternion
