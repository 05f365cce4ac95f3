// A scene as an Odeint system: the Scene's structure (scene/scene.hpp) with
// the constants the dynamics precompute (dynamics/model.hpp) and the state
// derivative.
//
//     auto arm = flange::scene(World<"world">{}, Revolute<"joint", axis::z>{}, …, connect<…>, …);
//     arm(x, dxdt, t);                      // ẋ = f(t, x): the Boost.Odeint system signature
//
// The state is x = (q, v): every joint's coordinates, then every joint's
// rates, joints in scene order. q̇ comes from each joint (q̇ = v for one-axis
// joints, a quaternion's rate for a Spherical joint), v̇ from the recursive
// algorithms (dynamics/forward_dynamics.hpp).
#pragma once
#include "flange/detail/inline.hpp"
#include <array>
#include <utility>

#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/scene/scene.hpp"

namespace flange {

template <class S>
class System : public S {
 public:
  using scene_type = S;
  using model_type = detail::dynamics_model<S::tree.n_links, (S::topology.n_sets == 0 ? 1 : S::topology.n_sets)>;

  explicit System(S s) : S(std::move(s)), model_(detail::build_model(static_cast<const S&>(*this))) {}

  /// Constants the dynamics precompute (link inertias, set poses).
  [[nodiscard]] const model_type& model() const { return model_; }

  /// ẋ = f(x, t): q̇ from each joint, v̇ by the algorithm the scene's type
  /// calls for. Works for any container with data() and size() (std::array,
  /// std::vector, Eigen vectors) and any scalar type.
  template <class State, class T>
  void operator()(const State& x, State& dxdt, const T t) const {
    static_assert(detail::report_list<(S::topology.ok() ? S::tree.loop : -1), diagnostic::kinematic_loop,
                                      typename S::component_types>::value);
    static_assert(S::template report_cut_off<(S::topology.ok() && S::tree.loop < 0 ? S::tree.floating : -1),
                                             diagnostic::not_tied_through_joints>());
    if constexpr (S::joints_complete) derivative(x, dxdt, t);  // else the scene has said what is missing
  }

 private:
  template <class State, class T>
  void derivative(const State& x, State& dxdt, const T t) const {
    S::require_state_size(x);
    S::require_state_size(dxdt);
    using V = std::remove_cvref_t<decltype(x[0])>;
    const V* xs = x.data();
    V* d = dxdt.data();
    const V* q = xs;
    const V* v = xs + S::n_q;
    detail::for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      using LI = detail::link_info<S, decltype(l)::value>;
      this->template component<LI::joint>().qdot(q + LI::q, v + LI::v, d + LI::q);
    });
    accelerations(*this, static_cast<V>(t), q, v, d + S::n_q);
  }

  model_type model_;
};

/// Builds a scene from components and connections, in any order: its
/// structure (scene/scene.hpp) and its dynamics.
template <class... Args>
auto scene(Args... args) {
  auto s = compose(std::move(args)...);
  return System<decltype(s)>(std::move(s));
}

/// The state with every joint at its neutral configuration (angles and
/// offsets zero, quaternions the identity) and at rest.
template <class S>
typename S::state_type neutral_state(const S& scene) {
  typename S::state_type x{};
  detail::for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = detail::link_info<S, decltype(l)::value>;
    const auto n = scene.template component<LI::joint>().neutral();
    for (int i = 0; i < LI::nq; ++i) x[LI::q + i] = n[i];
  });
  return x;
}

/// Keeps every joint's coordinates valid (a quaternion back to unit norm):
/// a projection between steps, for long runs.
template <class S, class State>
void normalize(const S& scene, State& x) {
  S::require_state_size(x);
  detail::for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = detail::link_info<S, decltype(l)::value>;
    scene.template component<LI::joint>().normalize(x.data() + LI::q);
  });
}

namespace detail {
/// The joint named Name in scene S, checked at compile time (a misspelt
/// name is one error listing the valid ones, scene/named_state.hpp).
template <class S, fixed_string Name>
struct named_joint {
  static constexpr int found = joint_named<S, Name>();
  static constexpr int index = found >= 0 ? found : joint_indices<S>()[0];  // no second error after the first
  using type = typename S::template component_type<index>;
};
template <class S, class State, int C>
void write_joint(const S& scene, State& x, const typename S::template component_type<C>::state& value) {
  std::array<double, S::template component_type<C>::nq> q;
  std::array<double, S::template component_type<C>::nv> v;
  scene.template component<C>().write_state(value, q.data(), v.data());
  for (std::size_t i = 0; i < q.size(); ++i) x[S::tree.q_offset[C] + i] = q[i];
  for (std::size_t i = 0; i < v.size(); ++i) x[S::n_q + S::tree.v_offset[C] + i] = v[i];
}
}  // namespace detail

/// Sets the named joint's coordinates and rates in x from its state type
/// (Revolute: {.q, .v}; Spherical: {.R = orientation::…, .w}; FreeMotion:
/// {.r, .v, .R, .w}; Universal, Cylindrical, Planar: {.q = {…}, .v = {…}}),
/// checked: an orientation must be a rotation, every number finite.
template <fixed_string Name, class S, class State>
void set_joint(const S& scene, State& x, const typename detail::named_joint<S, Name>::type::state& value) {
  S::require_state_size(x);
  detail::write_joint<S, State, detail::named_joint<S, Name>::index>(scene, x, value);
}

/// The state with the named joints set and every other joint at its neutral
/// configuration and at rest:
///
///   auto x0 = initial_state<"shoulder", "elbow">(arm, {.q = 0.3}, {.q = -0.2, .v = 1});
///
/// Each value has its joint's state type (see set_joint); the names are
/// checked at compile time, and a name given twice is an error.
template <fixed_string... Names, class S>
typename S::state_type initial_state(const S& scene,
                                     const typename detail::named_joint<S, Names>::type::state&... values) {
  constexpr std::array<int, sizeof...(Names)> idx{detail::named_joint<S, Names>::index...};
  constexpr int twice = [&] {
    for (std::size_t i = 0; i < idx.size(); ++i)
      for (std::size_t j = i + 1; j < idx.size(); ++j)
        if (idx[i] == idx[j]) return int(i);
    return -1;
  }();
  if constexpr (twice >= 0) {
    constexpr std::array<std::string_view, sizeof...(Names)> names{Names.view()...};
    (void)sizeof(diagnostic::joint_named_twice<
                 member<fixed_string<names[twice].size() + 1>(names[twice])>, void>);
  }
  auto x = neutral_state(scene);
  (detail::write_joint<S, typename S::state_type, detail::named_joint<S, Names>::index>(scene, x, values), ...);
  return x;
}

/// Throws parameter_error naming the joint if some joint's coordinates are
/// not valid (a quaternion far from unit norm): an input mistake, not drift.
template <class S, class State>
void check_coordinates(const S& scene, const State& x) {
  detail::for_links<S>([&](auto l) {
    using LI = detail::link_info<S, decltype(l)::value>;
    const auto& j = scene.template component<LI::joint>();
    if constexpr (requires { j.check_coordinates(x.data()); }) j.check_coordinates(x.data() + LI::q);
  });
}

}  // namespace flange
