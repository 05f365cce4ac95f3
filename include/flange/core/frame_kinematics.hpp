// The motion of one frame, as recovered from a simulated state: what the
// paper's potential variables r and R are, plus their time derivatives.
#pragma once
#include "flange/math/types.hpp"

namespace flange {

template <class T>
struct frame_kinematics {
  Vec3<T> r;      ///< world origin → frame origin, world coordinates
  Mat3<T> R;      ///< rotates world into frame
  Vec3<T> v;      ///< ṙ, world coordinates
  Vec3<T> w;      ///< ω with ω̃ = R·Ṙ', frame coordinates
  Vec3<T> a;      ///< r̈, world coordinates
  Vec3<T> wd;     ///< ω̇, frame coordinates
};

/// A wrench: force and torque, in the coordinates the caller says.
template <class T>
struct wrench {
  Vec3<T> f;
  Vec3<T> n;
};

}  // namespace flange
