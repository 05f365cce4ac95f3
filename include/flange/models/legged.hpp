// A floating-base robot: a trunk on a FreeMotion joint with Legs legs, each
// of Links revolute joints (hip about y, then knee and ankle about x, ...),
// each link a FixedTranslation to a body at its end. With the defaults, four
// 3-joint legs: 7 + 12 coordinates, 6 + 12 rates. Gravity along −y.
#pragma once
#include <array>
#include <utility>

#include <boost/hana/concat.hpp>
#include <boost/hana/flatten.hpp>
#include <boost/hana/prepend.hpp>
#include <boost/hana/unpack.hpp>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
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
};

namespace detail {
/// Joint J of leg K: its axis (hip about y, the others about x).
template <int J>
using leg_axis = std::conditional_t<J == 0, axis::y, axis::x>;

template <int K, int J, int Links>
auto leg_link(const legged_params& p) {
  namespace hana = boost::hana;
  constexpr auto j = indexed_name<"j", 100 * K + J>(), r = indexed_name<"r", 100 * K + J>(),
                 b = indexed_name<"b", 100 * K + J>();
  constexpr auto parent = [] {
    if constexpr (J == 0) return indexed_name<"h", K>() + ".frame_b";
    else return indexed_name<"r", 100 * K + J - 1>() + ".frame_b";
  }();
  return hana::make_tuple(Revolute<j, leg_axis<J>>{}, FixedTranslation<r>({.d = {0, -p.link_length, 0}}),
                          Body<b, cm::offset>({.m = p.link_mass, .J = p.link_inertia.asDiagonal(),
                                               .r_cm = {0, -0.5 * p.link_length, 0}}),
                          connect<parent, j + ".frame_a">, connect<j + ".frame_b", r + ".frame_a">,
                          connect<j + ".frame_b", b + ".frame_a">);
}

template <int K, int Links>
auto leg(const legged_params& p) {
  namespace hana = boost::hana;
  constexpr auto h = indexed_name<"h", K>();
  const double sx = (K % 2 ? -1 : 1) * p.hip_x, sz = (K / 2 ? -1 : 1) * p.hip_z;
  auto hip = hana::make_tuple(FixedTranslation<h>({.d = {sx, 0, sz}}), connect<"trunk.frame_a", h + ".frame_a">);
  auto links = [&]<int... J>(std::integer_sequence<int, J...>) {
    return hana::flatten(hana::make_tuple(leg_link<K, J, Links>(p)...));
  }(std::make_integer_sequence<int, Links>{});
  return hana::concat(hip, links);
}
}  // namespace detail

/// The floating-base robot (see above).
template <int Legs = 4, int Links = 3>
auto legged(const legged_params& p = {}) {
  namespace hana = boost::hana;
  static_assert(Legs >= 1 && Legs <= 9 && Links >= 1 && Links <= 99);
  auto base = hana::make_tuple(World<"world">{}, FreeMotion<"base">{},
                               Body<"trunk">({.m = p.trunk_mass, .J = p.trunk_inertia.asDiagonal()}),
                               connect<"world.frame_b", "base.frame_a">, connect<"base.frame_b", "trunk.frame_a">);
  auto legs = [&]<int... K>(std::integer_sequence<int, K...>) {
    return hana::flatten(hana::make_tuple(detail::leg<K, Links>(p)...));
  }(std::make_integer_sequence<int, Legs>{});
  return hana::unpack(hana::concat(base, legs), [](auto... a) { return scene(std::move(a)...); });
}

}  // namespace flange::models
