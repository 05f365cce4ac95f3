// A floating-base robot: a trunk on a FreeMotion joint with Legs legs, each
// of Links revolute joints (hip about y, then knee and ankle about x, ...),
// each link a FixedTranslation to a body at its end. With the defaults, four
// 3-joint legs: 7 + 12 coordinates, 6 + 12 rates. Gravity along −y. With
// Feet, each leg ends in a sphere that touches the ground, the half-space
// y ≤ −ground_depth (a Contact "foot<K>" per leg, forces/contact.hpp); with
// Belly also the trunk, a box (Contact "belly"), so that a robot whose legs
// give way comes to rest on it. Given a drive, each joint drives itself
// with it: drive(joint_tag<name>, t, x) is the joint's torque, the joint
// read by name (q<decltype(tag)::name>(x)); the joints are "j<K><J>" (leg K,
// joint J counted from the hip: "j0", "j1", "j2" on leg 0, "j100" … on leg 1).
#pragma once
#include <array>
#include <type_traits>
#include <utility>

#include <boost/hana/concat.hpp>
#include <boost/hana/flatten.hpp>
#include <boost/hana/prepend.hpp>
#include <boost/hana/unpack.hpp>

#include "flange/components/body.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/contact.hpp"
#include "flange/joints/free_motion.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

struct legged_params {
  double trunk_mass = 10.0;
  Vec3d trunk_inertia = Vec3d(0.1, 0.3, 0.25);
  double link_mass = 0.6;
  double link_length = 0.25;
  Vec3d link_inertia = Vec3d(0.004, 0.0005, 0.004);
  double hip_x = 0.3, hip_z = 0.15;  ///< hip positions on the trunk: (±hip_x, 0, ±hip_z)
  // With feet:
  double foot_radius = 0.03;
  double ground_depth = 0.78;  ///< the ground is y ≤ −ground_depth (legs straight down touch it)
  contact_material foot{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7};
  contact_material ground{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7};
  double transition_velocity = 1e-3;     ///< the feet's friction: static friction peaks at this slip speed [m/s]
  Vec3d belly = Vec3d(0.35, 0.05, 0.2);  ///< with Belly: the trunk's box, half extents about its centre
};

/// A legged robot whose joints are not driven.
struct undriven_legs {};

namespace detail {
/// Joint J of leg K: its axis (hip about y, the others about x).
template <int J>
using leg_axis = std::conditional_t<J == 0, axis::y, axis::x>;

template <int K, int J, int Links, class Drive>
auto leg_link(const legged_params& p, const Drive& drive) {
  namespace hana = boost::hana;
  constexpr auto j = indexed_name<"j", 100 * K + J>(), r = indexed_name<"r", 100 * K + J>(),
                 b = indexed_name<"b", 100 * K + J>();
  constexpr auto parent = [] {
    if constexpr (J == 0) return indexed_name<"h", K>() + ".frame_b";
    else return indexed_name<"r", 100 * K + J - 1>() + ".frame_b";
  }();
  auto joint = [&] {
    if constexpr (std::is_same_v<Drive, undriven_legs>) return Revolute<j, leg_axis<J>>{};
    else return revolute<j, leg_axis<J>>(drive_for<j>(drive));
  }();
  return hana::make_tuple(std::move(joint), FixedTranslation<r>({.d = {0, -p.link_length, 0}}),
                          Body<b, cm::offset>({.m = p.link_mass, .J = p.link_inertia.asDiagonal(),
                                               .r_cm = {0, -0.5 * p.link_length, 0}}),
                          connect<parent, j + ".frame_a">, connect<j + ".frame_b", r + ".frame_a">,
                          connect<j + ".frame_b", b + ".frame_a">);
}

/// Leg K's foot: a sphere at its last link's end against the ground.
template <int K, int Links>
auto foot(const legged_params& p) {
  namespace hana = boost::hana;
  constexpr auto f = indexed_name<"foot", K>();
  return hana::make_tuple(
      Contact<f, contact_shape::sphere, contact_shape::half_space>(
          {.a = {.radius = p.foot_radius}, .b = {.n = Vec3d::UnitY(), .offset = -p.ground_depth},
           .material_a = p.foot, .material_b = p.ground, .transition_velocity = p.transition_velocity}),
      connect<indexed_name<"r", 100 * K + Links - 1>() + ".frame_b", f + ".frame_a">,
      connect<"world.frame_b", f + ".frame_b">);
}

template <int K, int Links, bool Feet, class Drive>
auto leg(const legged_params& p, const Drive& drive) {
  namespace hana = boost::hana;
  constexpr auto h = indexed_name<"h", K>();
  const double sx = (K % 2 ? -1 : 1) * p.hip_x, sz = (K / 2 ? -1 : 1) * p.hip_z;
  auto hip = hana::make_tuple(FixedTranslation<h>({.d = {sx, 0, sz}}), connect<"trunk.frame_a", h + ".frame_a">);
  auto links = [&]<int... J>(std::integer_sequence<int, J...>) {
    return hana::flatten(hana::make_tuple(leg_link<K, J, Links>(p, drive)...));
  }(std::make_integer_sequence<int, Links>{});
  if constexpr (Feet) return hana::concat(hana::concat(hip, links), foot<K, Links>(p));
  else return hana::concat(hip, links);
}
}  // namespace detail

/// Joint "j<100·K + J>"'s J: its place on its leg, counted from the hip.
template <auto Name>
constexpr int place_on_leg() {
  int n = 0;
  for (char c : Name.view().substr(1)) n = 10 * n + (c - '0');
  return n % 100;
}

/// One PD law for every joint of a legged robot, toward a crouch: the
/// second joint of each leg at knee, the third at ankle (−2·knee keeps each
/// foot under its hip), the others at 0. A drive for legged(p, drive): it
/// reads each joint by its name.
struct crouch_drive {
  double kp = 1000, kd = 50;  ///< [N m/rad], [N m s/rad]
  double knee = 0.4;          ///< [rad]
  template <class Tag, class T, class X>
  T operator()(Tag, const T&, const X& x) const {
    constexpr auto name = Tag::name;
    constexpr int J = place_on_leg<name>();
    const double target = J == 1 ? knee : J == 2 ? -2 * knee : 0.0;
    return T(kp) * (T(target) - q<name>(x)) - T(kd) * v<name>(x);
  }
};

/// The floating-base robot (see above).
template <int Legs = 4, int Links = 3, bool Feet = false, bool Belly = false, class Drive = undriven_legs>
auto legged(const legged_params& p = {}, Drive drive = {}) {
  namespace hana = boost::hana;
  static_assert(Legs >= 1 && Legs <= 9 && Links >= 1 && Links <= 99);
  auto base = hana::make_tuple(World<"world">{}, FreeMotion<"base">{},
                               Body<"trunk">({.m = p.trunk_mass, .J = p.trunk_inertia.asDiagonal()}),
                               connect<"world.frame_b", "base.frame_a">, connect<"base.frame_b", "trunk.frame_a">);
  auto belly = [&] {
    if constexpr (Belly)
      return hana::make_tuple(Contact<"belly", contact_shape::box, contact_shape::half_space>(
                                  {.a = {.half_extents = p.belly, .corner_radius = 0.01},
                                   .b = {.n = Vec3d::UnitY(), .offset = -p.ground_depth},
                                   .material_a = p.ground, .material_b = p.ground,
                                   .transition_velocity = p.transition_velocity}),
                              connect<"base.frame_b", "belly.frame_a">, connect<"world.frame_b", "belly.frame_b">);
    else return hana::make_tuple();
  }();
  auto legs = [&]<int... K>(std::integer_sequence<int, K...>) {
    return hana::flatten(hana::make_tuple(detail::leg<K, Links, Feet>(p, drive)...));
  }(std::make_integer_sequence<int, Legs>{});
  return hana::unpack(hana::concat(hana::concat(base, belly), legs), [](auto... a) { return scene(std::move(a)...); });
}

/// The robot at rest in crouch_drive's crouch (knees at `knee`, ankles at
/// −2·knee, the trunk at the origin, level): with the default legs and
/// ground, its feet 4 cm above the ground for knee = 0.4.
template <int Legs = 4, class S>
[[nodiscard]] typename S::state_type crouched_state(const S& scene, double knee = 0.4) {
  auto x = neutral_state(scene);
  flange::detail::static_for<Legs>([&](auto k) {
    constexpr int K = decltype(k)::value;
    x[S::q_offset(indexed_name<"j", 100 * K + 1>().view())] = knee;
    x[S::q_offset(indexed_name<"j", 100 * K + 2>().view())] = -2 * knee;
  });
  return x;
}

}  // namespace flange::models
