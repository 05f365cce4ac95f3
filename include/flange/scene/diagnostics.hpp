// Compile-time diagnostics. Each structural mistake instantiates one of these
// templates with the offending component or connection as its argument, so
// that the compiler prints both the message (what is wrong and the fix) and
// the culprit's type, e.g.
//
//   In instantiation of 'struct flange::diagnostic::not_connected_to_world<flange::Body<"mass">>':
//   error: static assertion failed: flange: this component is not tied to the World ...
//
// See docs/diagnostics.md for each message with an example.
#pragma once
#include "flange/detail/always_false.hpp"
#include "flange/detail/closest_name.hpp"
#include "flange/detail/fixed_string.hpp"

namespace flange {

/// The tags the messages' template arguments are made of, out of the way of
/// a user's own names (using namespace flange brings none of them in).
namespace diagnostic {

template <int N> struct equations_declared {};
template <int N> struct equations_needed {};
template <int N> struct unknowns {};
template <int N> struct state_size_given {};
template <int N> struct state_size_needed {};

/// The valid name closest to a misspelt one (shown by the compiler).
template <fixed_string Name>
struct did_you_mean {};

/// did_you_mean<the entry of Names closest to Name>.
template <const auto& Names, fixed_string Name>
using suggest = did_you_mean<fixed_string<Names[detail::closest_name(Name.view(), Names)].size() + 1>(
    Names[detail::closest_name(Name.view(), Names)])>;

template <class Connection, class Closest>
struct connection_names_no_frame {
  static_assert(always_false<Connection>,
                "flange: this connect<\"component.frame\", ...> (the first template argument) names a frame that "
                "does not exist; did you mean the second? (World has frame_b, Body has frame_a, the others frame_a "
                "and frame_b)");
};
template <class Connection>
struct frame_listed_twice_in_connection {
  static_assert(always_false<Connection>,
                "flange: this connection lists the same frame twice; a connection joins two different frames");
};
template <class Connection>
struct frame_connected_twice_in_one_set {
  static_assert(always_false<Connection>,
                "flange: this connection joins two frames that are already in one connection set through other "
                "connections, so its equations would be redundant; remove it");
};
template <class Component>
struct duplicate_component_name {
  static_assert(always_false<Component>,
                "flange: two components have this name; give every component of a scene a unique name");
};
template <class... Components>
struct no_world {
  static_assert(always_false<Components...>,
                "flange: the scene has no World; add World<\"world\">{} and connect its frame_b");
};
template <class SecondWorld>
struct two_worlds {
  static_assert(always_false<SecondWorld>,
                "flange: the scene has a second World (this one); a scene has exactly one World, remove one");
};
template <class Component>
struct not_connected_to_world {
  static_assert(always_false<Component>,
                "flange: this component is not tied to the World by any connection path; connect one of its frames "
                "to the World's frame_b, directly or through other components");
};
template <class Component, class Declared, class Needed>
struct unbalanced_component {
  static_assert(always_false<Component>,
                "flange: unbalanced scene: this component declares a different number of scalar equations than it "
                "has unknowns minus flow variables (the counts are the template arguments); fix its equations()");
};
template <class Counts>
struct unbalanced_scene {
  static_assert(always_false<Counts>,
                "flange: unbalanced scene: the number of scalar equations differs from the number of unknowns (the "
                "counts are the template arguments); check each component's equations()");
};
template <class Component>
struct kinematic_loop {
  static_assert(always_false<Component>,
                "flange: this component closes a loop that no joint can cut (a loop of rigid components only, or "
                "a joint whose two frames are connected to each other), so nothing in it can move; remove it");
};
template <class Joint>
struct joint_cannot_close_loop {
  static_assert(always_false<Joint>,
                "flange: this joint closes a kinematic loop, and no joint of the loop can be cut in its place: each "
                "has a drive or an axis law (a Prismatic's force input counts as a force of its own), whose force "
                "would act on a coordinate the state does not have; give the loop one joint without a force of its "
                "own (any kind but Prismatic)");
};
template <class Component>
struct not_tied_through_joints {
  static_assert(always_false<Component>,
                "flange: this component is tied to the World only through force elements (or not at all), so it "
                "has no joint coordinates; connect it to the World through joints and rigid components");
};

template <class Component, class Frame>
struct frame_connected_to_nothing {
  static_assert(always_false<Component>,
                "flange: this frame of this component (the template arguments) is connected to nothing, so the "
                "component is cut off from the mechanism; add connect<\"component.frame\", \"other.frame\"> "
                "joining it to a frame of the mechanism");
};

template <class Component>
struct force_ends_in_one_set {
  static_assert(always_false<Component>,
                "flange: both ends of this line force element are in one connection set, so its line has no length "
                "and it acts on nothing; connect frame_a and frame_b to frames that move apart");
};

template <class Component>
struct contact_on_one_body {
  static_assert(always_false<Component>,
                "flange: both shapes of this Contact are on one body (its frame_a and frame_b are joined rigidly, "
                "with no joint between them), so they can never touch; pair a shape with one on another body or "
                "on the World");
};

template <class Component>
struct world_load_on_world {
  static_assert(always_false<Component>,
                "flange: this WorldForce or WorldTorque is connected to the World's own frame, so it acts on nothing "
                "that moves; connect its frame_b to a frame of the mechanism");
};

template <class Sizes>
struct wrong_state_size {
  static_assert(always_false<Sizes>,
                "flange: this state's size, fixed by its type, differs from the scene's n_state = 2·n_q (the sizes "
                "are the template arguments); declare it as Scene::state_type or eigen_state<Scene>");
};

}  // namespace diagnostic
}  // namespace flange
