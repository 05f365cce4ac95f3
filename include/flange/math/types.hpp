// The small fixed-size Eigen types flange computes with, all templated on the
// scalar type so that double, long double and dual numbers share one code path.
#pragma once
#include <Eigen/Core>

namespace flange {

template <class T> using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T> using Row3 = Eigen::Matrix<T, 1, 3>;
template <class T> using Mat3 = Eigen::Matrix<T, 3, 3>;
using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;

}  // namespace flange
