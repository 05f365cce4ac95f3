// Rotation matrices in the paper's conventions (seed-paper.md, "Prerequisites").
//
//   R rotates *world into frame*: a vector with world coordinates w has frame
//   coordinates R·w.  Hence R' maps frame coordinates back to world.
//
//   Axis-angle:   R = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//     This is the transpose of the usual (active) Rodrigues matrix: it is the
//     coordinate transform into a frame turned by +φ about n.
//   Tilde:        ã·b = a × b
//   Angular velocity:  ω̃ = R·Ṙ'   (ω resolved in the frame)
#pragma once
#include <cmath>

#include "flange/detail/inline.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/math/sincos.hpp"
#include "flange/math/types.hpp"

namespace flange {

/// Two unit vectors that complete the unit n to a right-handed orthonormal
/// basis (n, e1, e2): e1 is e_x (e_y where n is within about 25° of e_x)
/// with its part along n taken off, e2 = n × e1. The one rule flange uses
/// wherever it needs a direction normal to an axis (cut joints, loop
/// constraints, axis frames).
FLANGE_LAZY
void complete_basis(const Vec3<double>& n, Vec3<double>& e1, Vec3<double>& e2) {
  const Vec3<double> a = std::abs(n.x()) < 0.9 ? Vec3<double>::UnitX() : Vec3<double>::UnitY();
  e1 = (a - a.dot(n) * n).normalized();
  e2 = n.cross(e1);
}
FLANGE_COMMON(void complete_basis<0>(const Vec3<double>&, Vec3<double>&, Vec3<double>&))

/// The angle φ of the turn about the unit n that takes `from` to `to`, in
/// the paper's convention (R(n, φ)·from = to for their parts normal to n,
/// R = n·n' + (1 − n·n')·cos φ − ñ·sin φ): atan2(−(n × from)·to, from·to),
/// for a `from` normal to n. What a cut joint's angles are (core/joint.hpp).
template <class T>
[[nodiscard]] T turn_about(const Vec3d& n, const Vec3d& from, const Vec3<T>& to) {
  using std::atan2;
  return atan2(-n.cross(from).template cast<T>().dot(to), from.template cast<T>().dot(to));
}

/// ã, the matrix with ã·b = a × b.
template <class T>
[[nodiscard]] FLANGE_INLINE Mat3<T> tilde(const Vec3<T>& a) {
  Mat3<T> m;
  m(0, 0) = T(0), m(0, 1) = -a(2), m(0, 2) = a(1);
  m(1, 0) = a(2), m(1, 1) = T(0), m(1, 2) = -a(0);
  m(2, 0) = -a(1), m(2, 1) = a(0), m(2, 2) = T(0);
  return m;
}

/// The inverse of tilde on the skew-symmetric part: vex(ã) = a.
template <class T>
[[nodiscard]] Vec3<T> vex(const Mat3<T>& w) {
  return Vec3<T>((w(2, 1) - w(1, 2)) / T(2), (w(0, 2) - w(2, 0)) / T(2),
                 (w(1, 0) - w(0, 1)) / T(2));
}

/// R = n·n' + (1 − n·n')·cos φ − ñ·sin φ, for a unit axis n, written out
/// element by element (Rodrigues' form transposed), from cos φ and sin φ.
template <class T>
[[nodiscard]] FLANGE_INLINE Mat3<T> axis_rotation(const Vec3<T>& n, const cos_sin<T>& a) {
  const T& c = a.c;
  const T& s = a.s;
  const T k = T(1) - c;
  const T kx = k * n(0), ky = k * n(1), kz = k * n(2);
  const T sx = s * n(0), sy = s * n(1), sz = s * n(2);
  Mat3<T> R;
  R(0, 0) = kx * n(0) + c, R(0, 1) = kx * n(1) + sz, R(0, 2) = kx * n(2) - sy;
  R(1, 0) = ky * n(0) - sz, R(1, 1) = ky * n(1) + c, R(1, 2) = ky * n(2) + sx;
  R(2, 0) = kz * n(0) + sy, R(2, 1) = kz * n(1) - sx, R(2, 2) = kz * n(2) + c;
  return R;
}
template <class T>
[[nodiscard]] FLANGE_INLINE Mat3<T> axis_rotation(const Vec3<T>& n, const T& phi) {
  return axis_rotation<T>(n, cos_sin_of(phi));
}

/// ω from ω̃ = R·Ṙ'. Takes the skew part, so a slightly non-orthogonal R
/// gives the nearest angular velocity rather than garbage.
template <class T>
[[nodiscard]] Vec3<T> omega_from(const Mat3<T>& R, const Mat3<T>& Rdot) {
  return vex<T>(R * Rdot.transpose());
}

/// The three residues of the orientation equation R1 = R2, as Modelica's
/// Frames.Orientation.equalityConstraint defines them: small rotation angles
/// of R1·R2' about the three axes, and zero exactly when R1 = R2.
template <class T>
[[nodiscard]] Vec3<T> orientation_residue(const Mat3<T>& R1, const Mat3<T>& R2) {
  using std::atan2;
  const Mat3<T> A = R1 * R2.transpose();
  return Vec3<T>(atan2(A(2, 1), A(0, 0)), atan2(-A(2, 0), A(1, 1)), atan2(A(1, 0), A(2, 2)));
}

/// An orientation of one frame relative to another, in the paper's
/// convention: R rotates the reference frame's coordinates into the turned
/// frame's (R = n·n' + (1 − n·n')·cos θ − ñ·sin θ for a turn θ about n).
/// Initial states of 3-D joints and FixedRotation take one of these, so
/// nobody writes quaternion components by hand.
struct orientation {
  Mat3<double> R = Mat3<double>::Identity();

  /// Turned by angle about n (any non-zero length).
  FLANGE_LAZY
  static orientation axis_angle(const Vec3<double>& n, double angle) {
    return {axis_rotation<double>(n.normalized(), angle)};
  }
  /// Modelica's Cardan angles (axesRotations {1, 2, 3}): turned about x by
  /// a, then about the new y by b, then about the new z by c.
  FLANGE_LAZY
  static orientation cardan(double a, double b, double c) {
    return {axis_rotation<double>(Vec3<double>::UnitZ(), c) * axis_rotation<double>(Vec3<double>::UnitY(), b) *
            axis_rotation<double>(Vec3<double>::UnitX(), a)};
  }
  /// URDF's roll, pitch, yaw: turned about the reference's x by roll, then
  /// its y by pitch, then its z by yaw (fixed axes).
  FLANGE_LAZY
  static orientation rpy(double roll, double pitch, double yaw) {
    return {axis_rotation<double>(Vec3<double>::UnitX(), roll) * axis_rotation<double>(Vec3<double>::UnitY(), pitch) *
            axis_rotation<double>(Vec3<double>::UnitZ(), yaw)};
  }
  /// A rotation matrix in the paper's convention (checked orthogonal where it is used).
  FLANGE_LAZY
  static orientation matrix(const Mat3<double>& R) { return {R}; }
};

}  // namespace flange
