// A scene's bodies and its momentum at a state.
//
//   for (const auto& b : flange::bodies(scene)) b.name, b.m, b.r_cm, b.J;
//   const auto h = flange::momentum(scene, x);   // h.linear, h.angular (world frame, about its origin)
//
// Both read the bodies as the dynamics do (a Body's m, r_CM and J; a
// BodyShape's, from its shape), and momentum() the frames' poses and
// velocities as energy() does (the pose pass alone).
#pragma once
#include <array>
#include <string_view>
#include <utility>

#include "flange/dynamics/energy.hpp"

namespace flange {

/// One body of a scene: its name, mass, centre of mass (in the frame it is
/// attached by, frame_a) and inertia about the centre of mass (frame_a's axes).
struct body_info {
  std::string_view name;
  double m;
  Vec3d r_cm;
  Mat3d J;
};

namespace detail {
template <class S>
constexpr int count_bodies() {
  return []<int... I>(std::integer_sequence<int, I...>) {
    return (0 + ... + int(carries_body<typename S::template component_type<I>>));
  }(std::make_integer_sequence<int, S::n_components>{});
}
}  // namespace detail

/// Every body of the scene, in scene order.
template <class S>
[[nodiscard]] std::array<body_info, detail::count_bodies<S>()> bodies(const S& scene) {
  std::array<body_info, detail::count_bodies<S>()> r;
  int k = 0;
  for_each_component(scene, [&](auto i, const auto& c) {
    if constexpr (carries_body<std::remove_cvref_t<decltype(c)>>)
      r[k++] = {S::table.names[decltype(i)::value], c.m(), c.r_cm(), c.J()};
  });
  return r;
}

/// The system's momentum in world coordinates: linear Σ m·v_CM, and angular
/// about the world origin Σ (r_CM × m·v_CM + R·J·ω), R frame_a's orientation.
template <class T>
struct momentum_terms {
  Vec3<T> linear = Vec3<T>::Zero();
  Vec3<T> angular = Vec3<T>::Zero();
};

namespace detail {
/// The mass, first moment Σ m·r_CM and momentum of the bodies keep(i)
/// selects (i their component index), from the frames at a state.
template <class T>
struct mass_and_momentum {
  T m = T(0);
  Vec3<T> first_moment = Vec3<T>::Zero();
  momentum_terms<T> h;
};
template <class S, class T, class Keep>
[[nodiscard]] mass_and_momentum<T> momentum_of(const S& scene, const frames_at_state<S, T>& at, Keep keep) {
  mass_and_momentum<T> r;
  for_each_component(scene, [&](auto i, const auto& c) {
    if constexpr (carries_body<std::remove_cvref_t<decltype(c)>>) {
      if (!keep(decltype(i)::value)) return;
      const auto& k = at.frames[S::table.frame_base[decltype(i)::value]];
      // k.R turns world coordinates into frame_a's; k.w is in frame_a's, k.r and k.v in the world's.
      const Vec3<T> cm = c.r_cm().template cast<T>();
      const Vec3<T> rc = k.r + k.R.transpose() * cm;
      const Vec3<T> p = T(c.m()) * (k.v + k.R.transpose() * k.w.cross(cm));
      r.m += T(c.m());
      r.first_moment += T(c.m()) * rc;
      r.h.linear += p;
      r.h.angular += rc.cross(p) + k.R.transpose() * (c.J().template cast<T>() * k.w);
    }
  });
  return r;
}
}  // namespace detail

/// The momentum at state x = (q, v).
template <class S, class State, class T = double>
[[nodiscard]] momentum_terms<T> momentum(const S& scene, const State& x) {
  const detail::frames_at_state<S, T> at(scene, x);
  return detail::momentum_of(scene, at, [](int) { return true; }).h;
}

}  // namespace flange
