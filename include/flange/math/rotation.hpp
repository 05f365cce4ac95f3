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

#include "flange/math/types.hpp"

namespace flange {

/// ã, the matrix with ã·b = a × b.
template <class T>
[[nodiscard]] Mat3<T> tilde(const Vec3<T>& a) {
  Mat3<T> m;
  m << T(0), -a(2), a(1),  //
      a(2), T(0), -a(0),   //
      -a(1), a(0), T(0);
  return m;
}

/// The inverse of tilde on the skew-symmetric part: vex(ã) = a.
template <class T>
[[nodiscard]] Vec3<T> vex(const Mat3<T>& w) {
  return Vec3<T>((w(2, 1) - w(1, 2)) / T(2), (w(0, 2) - w(2, 0)) / T(2),
                 (w(1, 0) - w(0, 1)) / T(2));
}

/// R = n·n' + (1 − n·n')·cos φ − ñ·sin φ, for a unit axis n.
template <class T>
[[nodiscard]] Mat3<T> axis_rotation(const Vec3<T>& n, const T& phi) {
  using std::cos;
  using std::sin;
  const Mat3<T> nn = n * n.transpose();
  return nn + (Mat3<T>::Identity() - nn) * cos(phi) - tilde(n) * sin(phi);
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

}  // namespace flange
