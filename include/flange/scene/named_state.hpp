// Joints by name, resolved at compile time.
//
// An input callable f(t, x) sees the joint state x as a named_joint_state of
// its scene: q<"elbow">(x) and v<"elbow">(x) read the joint named "elbow"
// (a number for a one-coordinate joint, a fixed-size vector of its
// coordinates or rates otherwise) from the scene's table, with no search at
// run time. x.q(i) and x.v(i) still read by position. The rates are v, as in
// initial_state's {.q, .v}; qd is a deprecated name for them.
//
// A name that is not a joint of the scene is one error whose instantiation
// line lists the valid names:
//
//   In instantiation of 'struct flange::diagnostic::no_joint_named<flange::diagnostic::member<"elbw">,
//       flange::diagnostic::did_you_mean<"elbow">, flange::diagnostic::joints<"shoulder", "elbow">>'
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "flange/core/component.hpp"
#include "flange/detail/always_false.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/scene/diagnostics.hpp"
#include "flange/detail/fixed_string.hpp"

namespace flange {

namespace diagnostic {
/// The names a misspelt one could have been (shown by the compiler).
template <fixed_string... Names>
struct joints {};
template <class Name, class Closest, class Valid>
struct no_joint_named {
  static_assert(always_false<Name>,
                "flange: the scene has no joint of this name (the first template argument); did you mean the "
                "second? The joints it has are the third");
};
template <class Name>
struct joint_is_cut {
  static_assert(always_false<Name>,
                "flange: this joint (the template argument) closes a loop, and the scene cut it there: it has no "
                "coordinates in the state, where they are meant here (get_joint<\"name\">(scene, x) and recover read "
                "it from its frames; initial_state, close_loops and an input's q<\"name\">(x) take it by name, "
                "docs/loops.md); name a joint of the loop's tree instead");
};
template <class Name>
struct cut_joint_cannot_be_held {
  static_assert(always_false<Name>,
                "flange: this joint (the template argument) closes a loop and turns by a quaternion (a cut Spherical "
                "or FreeMotion): initial_state and close_loops cannot hold it; name a joint of the loop's tree "
                "instead, or write another joint of the loop last so that it is cut");
};
template <class Name, class Valid>
struct joint_named_twice {
  static_assert(always_false<Name>,
                "flange: this joint is given twice in one initial_state<...>; give each joint once");
};
}  // namespace diagnostic

namespace detail {

/// The component indices of S's joints, in scene order.
template <class S>
constexpr auto joint_indices() {
  std::array<int, S::n_joints> a{};
  int k = 0;
  for (int c = 0; c < S::n_components; ++c)
    if (S::tree.q_offset[c] >= 0) a[k++] = c;
  return a;
}
template <class S, std::size_t... I>
auto joint_names_of(std::index_sequence<I...>)
    -> diagnostic::joints<fixed_string<S::table.names[joint_indices<S>()[I]].size() + 1>(
        S::table.names[joint_indices<S>()[I]])...>;
/// diagnostic::joints<"a", "b", …>: S's joint names as a type, for errors.
template <class S>
using joint_names = decltype(joint_names_of<S>(std::make_index_sequence<S::n_joints>{}));

template <class S>
inline constexpr auto joint_name_table = [] {
  std::array<std::string_view, S::n_joints> a{};
  for (int k = 0; k < S::n_joints; ++k) a[k] = S::table.names[joint_indices<S>()[k]];
  return a;
}();

/// The component index of the joint named Name, or −1 after one diagnostic
/// listing the valid names.
template <class S, fixed_string Name>
constexpr int joint_named() {
  constexpr int c = S::index_of(Name.view());
  if constexpr (c >= 0 && S::tree.cut_of[c < 0 ? 0 : c] >= 0) {
    (void)sizeof(diagnostic::joint_is_cut<diagnostic::member<Name>>);
    return -1;
  } else if constexpr (c < 0 || S::tree.q_offset[c < 0 ? 0 : c] < 0) {
    (void)sizeof(
        diagnostic::no_joint_named<diagnostic::member<Name>, diagnostic::suggest<joint_name_table<S>, Name>, joint_names<S>>);
    return -1;
  } else {
    return c;
  }
}

/// The component index of the joint named `name`, at run time: throws
/// parameter_error naming the name and the closest joint, or saying that
/// the joint is cut (in a constant expression, the throw is the error).
template <class S>
constexpr int joint_named(std::string_view name) {
  const int c = S::index_of(name);
  if (c >= 0 && S::tree.cut_of[c] >= 0)
    throw parameter_error(concat("flange: joint \"", name, "\" closes a loop and is cut: it has no coordinates in ",
                                 "the state (its angle and rate are recovered: recover(scene, t, x).internal<\"",
                                 name, "\", \"phi\">())"));
  if (c < 0 || S::tree.q_offset[c] < 0) {
    const auto& names = joint_name_table<S>;
    throw parameter_error(concat("flange: the scene has no joint named \"", name, "\"",
                                 S::n_joints > 0 ? concat("; did you mean \"", names[closest_name(name, names)], "\"?")
                                                 : std::string()));
  }
  return c;
}

/// The component index of the joint named Name, a tree joint or a cut one,
/// or −1 after one diagnostic listing the valid names.
template <class S, fixed_string Name>
constexpr int joint_or_cut_named() {
  constexpr int c = S::index_of(Name.view());
  if constexpr (c >= 0 && S::tree.cut_of[c < 0 ? 0 : c] >= 0) return c;
  else return joint_named<S, Name>();
}

/// Cut K's coordinates cq and rates cv as its frames place them at (q, v):
/// its cut_state, what recover and get_joint report. Defined with the loops'
/// kinematics (dynamics/loops.hpp), which every scene with a loop includes.
template <class S, int K, class T>
void cut_joint_values(const S& scene, const T* q, const T* v, T* cq, T* cv);

/// The error of a view made without its scene that is asked for a cut joint.
FLANGE_LAZY
[[noreturn]] void cut_joint_needs_scene(std::string_view name) {
  throw parameter_error(concat("flange: joint \"", name, "\" closes a loop and is read from its frames, which ",
                               "this joint state cannot place: it was made as state_view<S>(q, v); make it as ",
                               "state_view(scene, q, v)"));
}
FLANGE_COMMON(void cut_joint_needs_scene<0>(std::string_view))
}  // namespace detail

/// The joint state of scene S as an input callable sees it: by position
/// (x.q(i), x.v(i)) as joint_state, and by name (q<"elbow">(x), v<"elbow">(x)).
/// A joint that closes a loop (cut) is read by name too, as its frames place
/// it: each such read is one pass over the tree's poses and velocities.
template <class T, class S>
struct named_joint_state : joint_state<T> {
  using scene_type = S;
  using joint_state<T>::q;
  using joint_state<T>::v;
  using joint_state<T>::qd;
  const S* scene_ = nullptr;  ///< for the cut joints' reads; null in a view made without it

  /// The named joint's coordinates: a T for a one-coordinate joint, else a
  /// vector of its nq coordinates (a quaternion's four, x, y, z, w as Eigen
  /// stores them). A cut joint's angles lie within (−π, π].
  template <fixed_string Name>
  [[nodiscard]] auto q() const {
    constexpr int c = detail::joint_or_cut_named<S, Name>();
    if constexpr (c < 0) return T(0);  // after the diagnostic, no second error
    else if constexpr (S::tree.cut_of[c] >= 0) return read<S::table.nq[c]>(cut<Name, c>().first.data());
    else return read<S::table.nq[c]>(this->q_ + S::tree.q_offset[c]);
  }
  /// The named joint's rates: a T for a one-coordinate joint, else its nv
  /// rates (a Spherical's angular velocity, a FreeMotion's v then ω).
  template <fixed_string Name>
  [[nodiscard]] auto v() const {
    constexpr int c = detail::joint_or_cut_named<S, Name>();
    if constexpr (c < 0) return T(0);
    else if constexpr (S::tree.cut_of[c] >= 0) return read<S::table.nv[c]>(cut<Name, c>().second.data());
    else return read<S::table.nv[c]>(this->v_ + S::tree.v_offset[c]);
  }
  template <fixed_string Name>
  [[deprecated("flange: the rates are v: write v<\"name\">(x) or x.v<\"name\">()")]] [[nodiscard]] auto qd() const {
    return v<Name>();
  }

 private:
  template <fixed_string Name, int C>
  auto cut() const {
    std::pair<std::array<T, S::table.nq[C]>, std::array<T, S::table.nv[C]>> r;
    if (!scene_) detail::cut_joint_needs_scene(Name.view());
    detail::cut_joint_values<S, S::tree.cut_of[C]>(*scene_, this->q_, this->v_, r.first.data(), r.second.data());
    return r;
  }
  template <int N>
  static auto read(const T* p) {
    if constexpr (N == 1) {
      return p[0];
    } else {
      Eigen::Matrix<T, N, 1> r;
      for (int i = 0; i < N; ++i) r[i] = p[i];
      return r;
    }
  }
};

/// The joint state of scene S at (q, v).
template <class S, class T>
named_joint_state<T, S> state_view(const S& scene, const T* q, const T* v) {
  return {{q, v, S::n_q}, &scene};
}
/// The same without the scene: its tree joints read by name as with it, a
/// cut joint not (parameter_error).
template <class S, class T>
named_joint_state<T, S> state_view(const T* q, const T* v) {
  return {{q, v, S::n_q}, nullptr};
}

/// q<"elbow">(x): the named joint's coordinates in an input's state x (the
/// form that works inside generic lambdas, where x.q<"elbow">() would need
/// `template`).
template <fixed_string Name, class T, class S>
[[nodiscard]] auto q(const named_joint_state<T, S>& x) {
  return x.template q<Name>();
}
/// v<"elbow">(x): the named joint's rates.
template <fixed_string Name, class T, class S>
[[nodiscard]] auto v(const named_joint_state<T, S>& x) {
  return x.template v<Name>();
}
/// The former name of v<"elbow">(x), kept for one release.
template <fixed_string Name, class T, class S>
[[deprecated("flange: the rates are v: write v<\"name\">(x)")]] [[nodiscard]] auto qd(const named_joint_state<T, S>& x) {
  return x.template v<Name>();
}

}  // namespace flange
