// Torque: relays an external torque M_ext (frame_a coordinates) into the
// system, acting on frame_b and reacting on frame_a.
//
//   F₁ = 0                   M₁ = M_ext
//   F₂ = 0                   M₂ = −(R₂·R₁')·M_ext
//
// Frames 1, 2 are frame_a, frame_b. M_ext is a constant 3-vector, a callable
// M_ext(t), or M_ext(t, x) of the joint state x (see joint_state). A force
// element: it adds no kinematic constraint.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"

namespace flange {

namespace diagnostic {
template <class F>
struct torque_input_type_not_given {
  static_assert(always_false<F>,
                "flange: this Torque's M_ext is a callable, but the Torque's input type was not given: write "
                "torque<\"name\">(f), or Torque<\"name\", decltype(f)>({.M_ext = f})");
};
}  // namespace diagnostic

template <fixed_string Name, class In = Vec3d>
class Torque {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Torque";
  static constexpr role kind = role::force;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 0> internals{};
  static constexpr bool needs_motion = false;  // a pure torque: the link rotations suffice
  static constexpr bool line_of_action = false;
  static constexpr bool exerts_force = false, exerts_torque = true;
  /// Whether its torque reads the joint state (an input of (t, x)).
  static constexpr bool reads_state = input_reads_state<In>;

  struct params {
    input_slot<In, diagnostic::torque_input_type_not_given> M_ext;
  };
  explicit Torque(params p) : M_ext_(take_input(std::move(p.M_ext))) {
    if constexpr (is_constant_input<In>)
      detail::require_finite(name.view(), "Torque", "M_ext", M_ext_);
  }

  template <class T>
  [[nodiscard]] Vec3<T> torque(const T& t, const state_of<T> auto& x) const {
    return eval_input(M_ext_, t, x);
  }

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const input_node<In, shape::vec> M{{}, &M_ext_, "M_ext"};
    return boost::hana::make_tuple(eq(F_<0>, zero<shape::vec>{}),  //
                                   eq(F_<1>, zero<shape::vec>{}),  //
                                   eq(M_<0>, M),                   //
                                   eq(M_<1>, -(R_<1> * transpose(R_<0>) * M)));
  }

  /// What the element exerts at its frames, world coordinates: M_ext on
  /// frame_b's side, −M_ext on frame_a's (M_ext resolved in frame_a).
  template <class T>
  void wrenches(const T& t, const state_of<T> auto& x, const frame_kinematics<T>* k, wrench<T>* on) const {
    const Vec3<T> M = k[0].R.transpose() * torque(t, x);
    on[0] = {Vec3<T>::Zero(), -M};
    on[1] = {Vec3<T>::Zero(), M};
  }

 private:
  In M_ext_;
};

/// Torque<"motor">'s input type deduced: torque<"motor">(fn) or torque<"motor">(vec).
template <fixed_string Name, class In>
auto torque(In M_ext) {
  if constexpr (std::is_base_of_v<Eigen::MatrixBase<In>, In>) return Torque<Name, Vec3d>({Vec3d(M_ext)});
  else return Torque<Name, In>({std::move(M_ext)});
}

}  // namespace flange
