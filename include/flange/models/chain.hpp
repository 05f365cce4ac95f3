// An N-link pendulum chain: World — Revolute j0 — FixedTranslation r0 — Body b0
// at r0.frame_b, where the next joint j1 sits, and so on.
//
// Axes<I> chooses link I's joint axis type: axis::z for every link gives a
// planar chain with compile-time axes; axis::any with run-time axes gives a
// spatial chain. The effects are types too: Law is every joint's axis law
// (axis_law::spring_damper uses chain_params::stiffness and damping), Gravity the World's,
// Inertia the bodies' (inertia_kind::point makes them point masses).
#pragma once
#include <array>
#include <random>
#include <type_traits>
#include <utility>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

template <int N>
struct chain_params {
  std::array<Vec3d, N> axis;  ///< used where the axis type is axis::any
  std::array<Vec3d, N> d;     ///< joint to next joint (and body), link coordinates
  std::array<double, N> m;
  std::array<Mat3d, N> J;
  Vec3d g = Vec3d(0, -9.81, 0);
  double stiffness = 0, damping = 0;  ///< every joint's c and d, with axis_law::spring_damper
};

/// Parameters of a random chain, drawn from rng: unit axes tilted up to 45°
/// from z, links 0.2–1 long with offsets up to 0.1 across, masses 0.2–1 and
/// one inertia for all. The benchmarks and probes draw their chains (and then
/// their states, from the same rng) here, so that they measure one model.
template <int N, class Rng>
chain_params<N> random_chain_params(Rng& rng) {
  std::uniform_real_distribution<double> u(0.2, 1.0), s(-1, 1);
  chain_params<N> p;
  for (int i = 0; i < N; ++i) {
    p.axis[i] = Vec3d(s(rng), s(rng), 1).normalized();
    p.d[i] = Vec3d(u(rng), 0.1 * s(rng), 0.1 * s(rng));
    p.m[i] = u(rng);
    p.J[i] = Vec3d(0.05, 0.06, 0.07).asDiagonal();
  }
  return p;
}

/// chain's components and connections, as a structure without dynamics
/// (detail::scene_structure).
template <int N, template <int> class Axis, class Law, class Gravity, class Inertia>
auto chain_structure(const chain_params<N>& p) {
  return [&]<int... I, int... K>(std::integer_sequence<int, I...>, std::integer_sequence<int, K...>) {
    auto joint = [&]<int L>(std::integral_constant<int, L>) {
      using A = typename Axis<L>::type;
      using J = Revolute<indexed_name<"j", L>(), A, Law>;
      if constexpr (std::is_same_v<Law, axis_law::spring_damper>) return J({.n = p.axis[L], .c = p.stiffness, .d = p.damping});
      else if constexpr (A::fixed) return J{};
      else return J({.n = p.axis[L]});
    };
    auto body = [&]<int L>(std::integral_constant<int, L>) {
      using B = Body<indexed_name<"b", L>(), cm::at_frame, Inertia>;
      if constexpr (std::is_same_v<Inertia, inertia_kind::point>) return B({.m = p.m[L]});
      else return B({.m = p.m[L], .J = p.J[L]});
    };
    auto world = [&] {
      if constexpr (std::is_same_v<Gravity, gravity_kind::none>) return World<"world", Gravity>{};
      else return World<"world", Gravity>({.g = p.g});
    };
    return flange::detail::scene_structure(world(),                                                   //
                 joint(std::integral_constant<int, I>{})...,                                            //
                 FixedTranslation<indexed_name<"r", I>()>({.d = p.d[I]})...,                            //
                 body(std::integral_constant<int, I>{})...,                                             //
                 connect<"world.frame_b", "j0.frame_a">,                                                //
                 connect<indexed_name<"j", I>() + ".frame_b", indexed_name<"r", I>() + ".frame_a">...,  //
                 connect<indexed_name<"r", I>() + ".frame_b", indexed_name<"b", I>() + ".frame_a">...,  //
                 connect<indexed_name<"r", K>() + ".frame_b", indexed_name<"j", K + 1>() + ".frame_a">...);
  }(std::make_integer_sequence<int, N>{}, std::make_integer_sequence<int, N - 1>{});
}
/// chain's scene under a short name of its own (flange::renamed): the
/// functions its dynamics instantiate name chain_scene<N, …>, not its 3N + 1
/// components.
template <int N, template <int> class Axis, class Law, class Gravity, class Inertia>
struct chain_scene : decltype(chain_structure<N, Axis, Law, Gravity, Inertia>(std::declval<const chain_params<N>&>())) {};

/// A chain of N links with joint axis type Axis<I>::type for link I.
template <int N, template <int> class Axis, class Law = axis_law::none, class Gravity = gravity_kind::uniform,
          class Inertia = inertia_kind::full>
System<chain_scene<N, Axis, Law, Gravity, Inertia>> chain(const chain_params<N>& p) {
  return flange::detail::named_system<chain_scene<N, Axis, Law, Gravity, Inertia>>(
      chain_structure<N, Axis, Law, Gravity, Inertia>(p));
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
