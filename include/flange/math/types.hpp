// The small fixed-size Eigen types flange computes with, all templated on the
// scalar type so that double, long double and dual numbers share one code path.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, quaternions

#include "flange/detail/inline.hpp"

namespace flange {

template <class T> using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T> using Row3 = Eigen::Matrix<T, 1, 3>;
template <class T> using Mat3 = Eigen::Matrix<T, 3, 3>;
using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;
using Vec2d = Eigen::Vector2d;
using Mat2d = Eigen::Matrix2d;

/// A fixed-size vector or matrix of zeros, written entry by entry and forced
/// inline. Eigen's `M::Zero()` is an expression whose conversion to M GCC
/// compiles as a call once a translation unit has spent its inlining budget:
/// in the scale benchmark's unit of five planar chains, the 16-link chain's
/// articulated body made 32 such calls per derivative, none in a unit of its
/// own. Used where the passes build a zero.
template <class M>
FLANGE_INLINE M zeros() {
  M m;
  for (Eigen::Index i = 0; i < M::SizeAtCompileTime; ++i) m.data()[i] = typename M::Scalar(0);
  return m;
}

}  // namespace flange
