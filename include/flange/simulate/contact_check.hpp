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
// extent). One pose pass per accepted step, and nothing at all in a scene
// without a Contact.
#pragma once
#include <string_view>
#include <utility>

#include "flange/dynamics/energy.hpp"
#include "flange/simulate/checked.hpp"

namespace flange::detail {

/// Whether the scene has a Contact (a component that pairs shapes on two bodies).
template <class S>
constexpr bool has_contacts() {
  return []<int... C>(std::integer_sequence<int, C...>) {
    return (requires { S::template component_type<C>::pairs_two_bodies; } || ...);
  }(std::make_integer_sequence<int, S::n_components>{});
}

/// Throws simulation_error at (t, x) naming the first Contact whose shapes
/// overlap too deeply: more than half the smaller shape's size at the
/// start, more than all of it after a step.
template <class S, class State>
void check_contact_depths(const S& scene, const State& x, double t, bool at_start) {
  if constexpr (has_contacts<S>()) {
    const frames_at_state<S, double> fs(scene, x);
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (requires { Comp::pairs_two_bodies; }) {
              const auto& c = scene.template component<C>();
              const double depth = c.deepest(&fs.frames[S::table.frame_base[C]]);
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
