// The buffered gantry crane (examples/buffered_crane.cpp) driven by a PD
// controller on its cart, for ensembles over gains and loads: the cart
// (rail friction, viscous plus smooth Coulomb) is tied to the end of its rail
// by a spring-damper buffer and pushed by f = kp·(s* − s) − kd·ṡ toward s*;
// the load hangs from it on a rope. The controller is a type with run-time
// gains, so every gain and load gives the same scene type.
//
// x = (s, φ; ṡ, φ̇), φ = θ − π/2 with θ the load's angle from the downward
// vertical. At rest_state() the load hangs straight down and the cart sits
// where the buffer is unstretched (s = −0.5 m).
#pragma once
#include <numbers>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/line_force.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

/// The cart's PD controller: f = kp·(target − s) − kd·ṡ.
struct cart_pd {
  double kp = 10, kd = 6, target = 1.0;
  template <class T>
  T operator()(const T&, const joint_state<T>& x) const {
    return T(kp) * (T(target) - x.q(0)) - T(kd) * x.v(0);
  }
};

struct controlled_crane_params {
  cart_pd controller{};
  double m_cart = 1.0, m_load = 0.5, rope = 1.0;
  double rail_d = 0.2, rail_f_c = 0.3;                       ///< rail friction: viscous [N s/m], Coulomb [N]
  double buffer_c = 40.0, buffer_d = 2.0, buffer_s0 = 1.0;  ///< the buffer's spring [N/m], damper [N s/m], length [m]
};

inline auto controlled_crane(const controlled_crane_params& p = {}) {
  return scene(World<"world">({.g = {0, -9.81, 0}}),
               Prismatic<"rail", axis::x, cart_pd, axis_law::friction>(
                   {.f = p.controller, .d = p.rail_d, .f_c = p.rail_f_c, .v_s = 1e-3}),
               Body<"cart">({.m = p.m_cart, .J = Mat3d::Identity() * 0.1}), Revolute<"pivot", axis::z>{},
               FixedTranslation<"rope">({.d = {p.rope, 0, 0}}), PointMass<"load">({.m = p.m_load}),
               FixedTranslation<"end">({.d = {-(p.buffer_s0 + 0.5), 0, 0}}),
               SpringDamper<"buffer">({.c = p.buffer_c, .s0 = p.buffer_s0, .d = p.buffer_d}),
               connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
               connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rope.frame_a">,
               connect<"rope.frame_b", "load.frame_a">, connect<"world.frame_b", "end.frame_a">,
               connect<"end.frame_b", "buffer.frame_a">, connect<"rail.frame_b", "buffer.frame_b">);
}
using controlled_crane_scene = decltype(controlled_crane());

/// The load hanging straight down, the cart at rest where the buffer is unstretched.
inline controlled_crane_scene::state_type controlled_crane_rest() {
  return {-0.5, -std::numbers::pi / 2, 0.0, 0.0};
}

}  // namespace flange::models
