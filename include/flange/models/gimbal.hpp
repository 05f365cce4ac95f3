// A spatial gimbal: three revolute joints about x, y and z, each with a body
// on its own frame_b (its link's origin) and a FixedTranslation to the next
// joint. The bodies' inertia kinds are types: the first and last take I1,
// the middle one I2 (inertia J_mid when I2 is not a point mass). With bodies
// at link origins, a point or diagonal inertia known from the type lets the
// dynamics skip products (docs/effects.md).
#pragma once
#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

template <class I1, class I2>
auto gimbal(const Vec3d& J_mid = Vec3d(0.05, 0.01, 0.05)) {
  auto body = [](auto b, const Vec3d& Jd) {
    using B = decltype(b);
    if constexpr (B::is_point) return B({.m = 0.7});
    else return B({.m = 0.7, .J = Jd.asDiagonal()});
  };
  return scene(World<"world">{}, Revolute<"j0", axis::x>{}, Revolute<"j1", axis::y>{}, Revolute<"j2", axis::z>{},
               body(Body<"b0", cm::at_frame, I1>({.m = 1}), Vec3d(0.02, 0.03, 0.04)),
               body(Body<"b1", cm::at_frame, I2>({.m = 1}), J_mid),
               body(Body<"b2", cm::at_frame, I1>({.m = 1}), Vec3d(0.03, 0.03, 0.02)),
               FixedTranslation<"r0">({.d = {0.3, 0.1, 0.0}}), FixedTranslation<"r1">({.d = {0.2, -0.1, 0.4}}),
               connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "b0.frame_a">,
               connect<"j0.frame_b", "r0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
               connect<"j1.frame_b", "b1.frame_a">, connect<"j1.frame_b", "r1.frame_a">,
               connect<"r1.frame_b", "j2.frame_a">, connect<"j2.frame_b", "b2.frame_a">);
}

}  // namespace flange::models
