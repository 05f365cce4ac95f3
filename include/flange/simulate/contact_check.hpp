// A checked run's contact checks (integrate.hpp): shapes that overlap by far
// more than a compliant contact lets them are not a state to integrate from
// but a mistake (a scene that starts inside the ground) or a breakdown (a
// contact too soft for its load, or a step that tunnelled). Either throws,
// with the time and the state, naming the Contact:
//
//   at the start   deeper than half the smaller shape's size
//   after a step   deeper than the smaller shape's size
//
// (the size: a sphere's or a capsule's radius, a box's smallest half
// extent). One pose pass per accepted step, over the contacts' links and
// their ancestors, and nothing at all in a scene without a Contact.
#pragma once
#include <array>
#include <string_view>
#include <utility>

#include "flange/dynamics/external.hpp"
#include "flange/dynamics/links.hpp"
#include "flange/simulate/checked.hpp"

namespace flange::detail {

/// Whether the scene has a Contact (a component that pairs shapes on two bodies).
template <class S>
constexpr bool has_contacts() {
  return []<int... C>(std::integer_sequence<int, C...>) {
    return (requires { S::template component_type<C>::pairs_two_bodies; } || ...);
  }(std::make_integer_sequence<int, S::n_components>{});
}

/// The links some Contact's frames sit on, the World's left out (link_poses' Keep).
template <class S>
struct contact_links {
  static constexpr std::array<bool, S::tree.n_links> value = [] {
    std::array<bool, S::tree.n_links> k{};
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            if constexpr (requires { S::template component_type<C>::pairs_two_bodies; })
              for (const int l : force_links<S, C>()) k[l] = true;
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    k[0] = false;
    return k;
  }();
};

/// Throws simulation_error at (t, x) naming the first Contact whose shapes
/// overlap too deeply: more than half the smaller shape's size at the
/// start, more than all of it after a step. The poses of the contacts'
/// links only, and of their frames.
template <class S, class State>
void check_contact_depths(const S& scene, const State& x, double t, bool at_start) {
  if constexpr (has_contacts<S>()) {
    S::require_state_size(x);
    std::array<double, S::n_q> q;
    std::array<double, S::n_v> v;
    for (int i = 0; i < S::n_q; ++i) q[i] = x[i];
    for (int i = 0; i < S::n_v; ++i) v[i] = x[S::n_q + i];
    const auto motions = link_motions<spatial_algebra, double, true>(scene, q.data());
    const auto lk = link_poses<S, double, contact_links<S>, velocity_in::link>(motions, v.data());
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (requires { Comp::pairs_two_bodies; }) {
              constexpr auto links = force_links<S, C>();
              const frame_kinematics<double> k[2] = {frame_from_link<S, C, 0>(scene, lk[links[0]]),
                                                     frame_from_link<S, C, 1>(scene, lk[links[1]])};
              const auto& c = scene.template component<C>();
              const double depth = c.deepest(k);
              const double size = c.geometry().size();
              if (depth > (at_start ? 0.5 : 1.0) * size) [[unlikely]]
                fail_at(at_start ? concat("Contact \"", Comp::name.view(), "\": its shapes overlap by ", brief(depth),
                                          " m at the start, more than half the smaller shape's size (", brief(size),
                                          " m); start them apart, or touching")
                                 : concat("Contact \"", Comp::name.view(), "\": its shapes overlap by ", brief(depth),
                                          " m, more than the smaller shape's size (", brief(size),
                                          " m): the contact is too soft for this load or speed (raise its "
                                          "stiffness), or a step passed through it (lower the tolerance)"),
                        x, t);
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
  } else {
    (void)scene, (void)x, (void)t, (void)at_start;
  }
}

}  // namespace flange::detail
