// The bars the spatial loop tests build their mechanisms of.
#pragma once
#include <flange/flange.hpp>

namespace flange::test {

/// A bar from frame_a to frame_b at r: 1 kg, I = m·L²/12 about every axis.
template <fixed_string Name>
auto bar_to(const Vec3d& r) {
  const double m = 1.0, L = r.norm();
  return BodyShape<Name>({.r = r, .r_cm = r / 2, .m = m, .I = Mat3d::Identity() * (m * L * L / 12)});
}

}  // namespace flange::test
