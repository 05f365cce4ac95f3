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
    static_assert(detail::report_list<(S::topology.ok() && S::tree.loop < 0 ? S::tree.floating : -1),
                                      diagnostic::not_tied_through_joints, typename S::component_types>::value);
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
/// The joint named Name in scene S, checked at compile time.
template <class S, fixed_string Name>
struct named_joint {
  static constexpr int index = S::index_of(Name.view());
  static_assert(index >= 0, "flange: the scene has no component of this name");
  using type = typename S::template component_type<(index < 0 ? 0 : index)>;
  static_assert(type::kind == role::joint, "flange: this component is not a joint");
};
}  // namespace detail

/// Sets the named joint's coordinates and rates in x from its state type
/// (Revolute: {.q, .v}; Spherical: {.R = orientation::…, .w}; FreeMotion:
/// {.r, .v, .R, .w}; Universal, Cylindrical, Planar: {.q = {…}, .v = {…}}),
/// checked: an orientation must be a rotation, every number finite.
template <fixed_string Name, class S, class State>
void set_joint(const S& scene, State& x, const typename detail::named_joint<S, Name>::type::state& value) {
  S::require_state_size(x);
  constexpr int c = detail::named_joint<S, Name>::index;
  std::array<double, S::template component_type<c>::nq> q;
  std::array<double, S::template component_type<c>::nv> v;
  scene.template component<c>().write_state(value, q.data(), v.data());
  for (std::size_t i = 0; i < q.size(); ++i) x[S::tree.q_offset[c] + i] = q[i];
  for (std::size_t i = 0; i < v.size(); ++i) x[S::n_q + S::tree.v_offset[c] + i] = v[i];
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
