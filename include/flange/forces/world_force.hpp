// WorldForce and WorldTorque: a force or a torque from outside the mechanism
// acting at one frame, like Modelica's Forces.WorldForce and WorldTorque.
//
//   WorldForce,  resolved in world:    F₁ = −R₁·f_ext     M₁ = 0
//   WorldForce,  resolved in frame_b:  F₁ = −f_ext        M₁ = 0
//   WorldTorque, resolved in world:    F₁ = 0             M₁ = −R₁·τ_ext
//   WorldTorque, resolved in frame_b:  F₁ = 0             M₁ = −τ_ext
//
// Frame 1 is the element's only frame, frame_b (as in Modelica). f_ext and
// τ_ext act on whatever frame_b is connected to, at its origin; the World takes
// the reaction. They are constants, callables of t, or of (t, x), like a
// Torque's M_ext.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"

namespace flange {

/// The coordinates an external force or torque is given in.
namespace resolve {
struct world {};    ///< world coordinates (the default)
struct frame_b {};  ///< the coordinates of the frame it acts on, turning with it
}  // namespace resolve

namespace load {
struct force {};
struct torque {};
}  // namespace load

namespace diagnostic {
template <class F>
struct world_load_input_type_not_given {
  static_assert(always_false<F>,
                "flange: this WorldForce's or WorldTorque's value is a callable, but its input type was not given: "
                "write WorldForce<\"name\", decltype(f)>({.value = f}) (or WorldTorque<…>)");
};
}  // namespace diagnostic

template <fixed_string Name, class What, class In = Vec3d, class Frame = resolve::world>
class WorldLoad {
 public:
  static constexpr bool is_force = std::is_same_v<What, load::force>;
  static constexpr bool in_world = std::is_same_v<Frame, resolve::world>;
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = is_force ? "WorldForce" : "WorldTorque";
  static constexpr role kind = role::force;
  static constexpr std::array<std::string_view, 1> frames{"frame_b"};
  static constexpr std::array<internal_decl, 0> internals{};
  static constexpr bool needs_motion = true;  // the frame's orientation and offset
  static constexpr bool line_of_action = false;
  static constexpr bool exerts_force = is_force, exerts_torque = !is_force;
  /// Whether its value reads the joint state (an input of (t, x)).
  static constexpr bool reads_state = input_reads_state<In>;

  struct params {
    input_slot<In, diagnostic::world_load_input_type_not_given> value;  ///< f_ext [N] or τ_ext [N m]
  };
  explicit WorldLoad(params p) : value_(take_input(std::move(p.value))) {
    if constexpr (is_constant_input<In>)
      detail::require_finite(name.view(), type_name, is_force ? "f_ext" : "tau_ext", value_);
  }

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const input_node<In, shape::vec> v{{}, &value_, is_force ? "f_ext" : "τ_ext"};
    auto flow = [&] {
      if constexpr (in_world) return -(R_<0> * v);
      else return -v;
    };
    if constexpr (is_force) return boost::hana::make_tuple(eq(F_<0>, flow()), eq(M_<0>, zero<shape::vec>{}));
    else return boost::hana::make_tuple(eq(F_<0>, zero<shape::vec>{}), eq(M_<0>, flow()));
  }

  /// What the element exerts at frame_b, world coordinates.
  template <class T>
  void wrenches(const T& t, const state_of<T> auto& x, const frame_kinematics<T>* k, wrench<T>* on) const {
    Vec3<T> v = eval_input(value_, t, x);
    if constexpr (!in_world) v = k[0].R.transpose() * v;
    if constexpr (is_force) on[0] = {v, Vec3<T>::Zero()};
    else on[0] = {Vec3<T>::Zero(), v};
  }

 private:
  In value_;
};

template <fixed_string Name, class In = Vec3d, class Frame = resolve::world>
using WorldForce = WorldLoad<Name, load::force, In, Frame>;
template <fixed_string Name, class In = Vec3d, class Frame = resolve::world>
using WorldTorque = WorldLoad<Name, load::torque, In, Frame>;

}  // namespace flange
