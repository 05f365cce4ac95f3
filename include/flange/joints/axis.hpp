// Joint axes. An axis known at compile time (axis::x, axis::y, axis::z) is a
// type: the joint then uses 2-D rotation arithmetic instead of a 3×3 product,
// and its axis is a vector along one coordinate (math/sparse.hpp). axis::any
// is a run-time unit vector, given at construction.
#pragma once
#include "flange/math/sparse.hpp"
#include "flange/math/types.hpp"

namespace flange::axis {

/// A coordinate axis, chosen at compile time.
template <int I>
struct coordinate {
  static_assert(I >= 0 && I < 3, "flange: a coordinate axis is x (0), y (1) or z (2)");
  static constexpr bool fixed = true;
  static constexpr int index = I;
  static Vec3d unit() { return Vec3d::Unit(I); }
};
using x = coordinate<0>;
using y = coordinate<1>;
using z = coordinate<2>;

/// An axis given at run time.
struct any {
  static constexpr bool fixed = false;
  static constexpr int index = -1;
};

/// The signed unit axis σ·n as a typed vector: along one coordinate for a
/// compile-time axis (its zeros are never multiplied), dense otherwise.
template <class T, class Axis, int Sign>
auto signed_unit(const Vec3d& n) {
  if constexpr (Axis::fixed) {
    (void)n;
    return axial<T, Axis::index>(T(Sign));
  } else {
    return to_svec(Vec3<T>((Sign * n).template cast<T>()));
  }
}

}  // namespace flange::axis
