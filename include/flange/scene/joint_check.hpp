// The joint concept (core/joint.hpp) checked at the scene, member by member,
// so that a user's own joint type that misses a member fails with one
// static_assert naming the joint and the member, not deep inside a pass.
#pragma once
#include "flange/core/joint.hpp"
#include "flange/detail/always_false.hpp"
#include "flange/detail/fixed_string.hpp"

namespace flange {

namespace diagnostic {
template <class Joint, class Member>
struct joint_lacks_member {
  static_assert(always_false<Joint>,
                "flange: this joint type lacks a member every joint declares (the member is the second template "
                "argument); see docs/architecture.md, \"Write your own joint\"");
};
template <class Joint>
struct joint_connected_backwards {
  static_assert(always_false<Joint>,
                "flange: this joint is connected with frame_b toward the World, which its type does not support; "
                "connect its frame_a toward the World (swap the frames in its two connections)");
};
}  // namespace diagnostic

namespace detail {
/// Reports the missing member (the one error the user sees) and lets the
/// scene's own check pass, so nothing else fails on top of it.
template <class J, fixed_string Name>
constexpr bool lacks() {
  (void)sizeof(diagnostic::joint_lacks_member<J, diagnostic::member<Name>>);
  return true;
}

template <class C>
constexpr bool check_joint() {
  namespace req = joint_requirements;
  if constexpr (C::kind != role::joint) return true;
  else if constexpr (!req::sizes<C>) return lacks<C, "static constexpr int nq, nv">();
  else if constexpr (!req::reversible<C>) return lacks<C, "static constexpr bool reversible">();
  else if constexpr (!req::neutral<C>) return lacks<C, "neutral()">();
  else if constexpr (!req::motion<C>) return lacks<C, "motion<T, Dir, NeedRotation>(q)">();
  else if constexpr (!req::motion_pose<C>) return lacks<C, "motion(q).E and .p">();
  else if constexpr (!req::motion_rates<C>) return lacks<C, "motion(q).w(v) and .pd(v) (a motion derived from motion_base<T> has pd = 0)">();
  else if constexpr (!req::motion_biases<C>) return lacks<C, "motion(q).w_bias(v) and .pd_bias(v) (derive the motion from motion_base<T> for zero biases)">();
  else if constexpr (!req::motion_project<C>) return lacks<C, "motion(q).project(n, f)">();
  else if constexpr (!req::motion_columns<C>) return lacks<C, "motion(q).col<k>()">();
  else if constexpr (!req::qdot<C>) return lacks<C, "qdot(q, v, qd)">();
  else if constexpr (!req::planar_info<C>) return lacks<C, "planar_normal(), moves_in_plane(k)">();
  else if constexpr (!req::internals_io<C>) return lacks<C, "write_internals(q, v, set), read_state(get, q, v)">();
  else return true;
}

template <class... Cs>
constexpr bool check_joints() {
  return (check_joint<Cs>() && ...);
}

/// Whether every joint models the concept (no diagnostic): what the dynamics
/// check before they compile anything that would fail on a missing member.
template <class C>
constexpr bool complete_joint() {
  if constexpr (C::kind != role::joint) return true;
  else return Joint<C>;
}
}  // namespace detail
}  // namespace flange
