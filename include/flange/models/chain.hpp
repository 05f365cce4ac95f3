// An N-link pendulum chain: World — Revolute j0 — FixedTranslation r0 — Body b0
// at r0.frame_b, where the next joint j1 sits, and so on.
//
// Axes<I> chooses link I's joint axis type: axis::z for every link gives a
// planar chain with compile-time axes; axis::any with run-time axes gives a
// spatial chain.
#pragma once
#include <array>
#include <utility>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/scene/scene.hpp"

namespace flange::models {

template <int N>
struct chain_params {
  std::array<Vec3d, N> axis;  ///< used where the axis type is axis::any
  std::array<Vec3d, N> d;     ///< joint to next joint (and body), link coordinates
  std::array<double, N> m;
  std::array<Mat3d, N> J;
  Vec3d g = Vec3d(0, -9.81, 0);
};

/// A chain of N links with joint axis type Axis<I>::type for link I.
template <int N, template <int> class Axis>
auto chain(const chain_params<N>& p) {
  return [&]<int... I, int... K>(std::integer_sequence<int, I...>, std::integer_sequence<int, K...>) {
    auto joint = [&]<int L>(std::integral_constant<int, L>) {
      using A = typename Axis<L>::type;
      using J = Revolute<indexed_name<"j", L>(), A>;
      if constexpr (A::fixed) return J{};
      else return J({.n = p.axis[L]});
    };
    return scene(World<"world">({.g = p.g}),                                                           //
                 joint(std::integral_constant<int, I>{})...,                                            //
                 FixedTranslation<indexed_name<"r", I>()>({.d = p.d[I]})...,                            //
                 Body<indexed_name<"b", I>()>({.m = p.m[I], .J = p.J[I]})...,                           //
                 connect<"world.frame_b", "j0.frame_a">,                                                //
                 connect<indexed_name<"j", I>() + ".frame_b", indexed_name<"r", I>() + ".frame_a">...,  //
                 connect<indexed_name<"r", I>() + ".frame_b", indexed_name<"b", I>() + ".frame_a">...,  //
                 connect<indexed_name<"r", K>() + ".frame_b", indexed_name<"j", K + 1>() + ".frame_a">...);
  }(std::make_integer_sequence<int, N>{}, std::make_integer_sequence<int, N - 1>{});
}

template <int>
struct planar_axes {
  using type = axis::z;
};
template <int>
struct runtime_axes {
  using type = axis::any;
};

}  // namespace flange::models
