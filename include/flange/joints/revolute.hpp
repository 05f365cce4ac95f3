// Revolute: rotation about a fixed axis n (unit, in frame_a = frame_b coordinates).
//
//   R_rel = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//   r₁ = r₂                  F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₂ = −R_rel·M₁
//                            0  = M₂·n
//
// Frames 1, 2 are frame_a, frame_b; φ and R_rel are internal variables. R_rel
// is the transpose of the active Rodrigues matrix: frame_b is frame_a turned by
// +φ about n. The joint transmits no torque about n: it is driven by a Torque
// element, or by nothing.
//
// Revolute<"elbow", axis::z> fixes the axis at compile time; Revolute<"elbow">
// takes it at construction.
//
// Revolute<"elbow", axis::z, axis_law::spring_damper> adds a linear spring
// (stiffness c, rest angle φ0) and damper (d) acting along the axis, like a
// Modelica SpringDamper on the joint's 1-D flange. The last equation becomes
//
//   M₂·n = c·(φ − φ0) + d·φ̇
//
// (the joint's own torque on frame_b's side is −c·(φ − φ0) − d·φ̇). A scene
// without it has no such arithmetic.
//
// Revolute<"elbow", axis::z, axis_law::friction> adds bearing friction: viscous
// d plus Coulomb F_c, regularised (smooth) by tanh over a speed v_s, so the
// stepper sees a smooth right-hand side and no stick-slip events:
//
//   M₂·n = d·φ̇ + F_c·tanh(φ̇ / v_s)
//
// Below |φ̇| ≈ v_s the joint creeps instead of sticking; choose v_s well below
// the speeds that matter (default 1e-3 rad/s).
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/components/component.hpp"
#include "flange/components/frame_kinematics.hpp"
#include "flange/joints/axis.hpp"
#include "flange/joints/axis_law.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

enum class joint_type { revolute, prismatic };


namespace detail {
template <class Axis, class Law>
struct revolute_params {
  Vec3d n = Vec3d::UnitZ();
};
template <int I>
struct revolute_params<axis::coordinate<I>, axis_law::none> {};
template <class Axis>
struct revolute_params<Axis, axis_law::spring_damper> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  double c = 0;              ///< stiffness [N m/rad]
  double d = 0;              ///< damping [N m s/rad]
  double phi0 = 0;           ///< rest angle [rad]
};
template <class Axis>
struct revolute_params<Axis, axis_law::friction> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  double d = 0;              ///< viscous friction [N m s/rad]
  double f_c = 0;            ///< Coulomb friction torque [N m]
  double v_s = 1e-3;         ///< regularisation speed [rad/s]: tanh(φ̇ / v_s)
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any, class Law = axis_law::none>
class Revolute {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Revolute";
  static constexpr role kind = role::joint;
  static constexpr joint_type type = joint_type::revolute;
  using axis_type = Axis;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"φ", expr::var_kind::scalar}, {"R_rel", expr::var_kind::rot}}};
  static constexpr bool has_spring_damper = std::is_same_v<Law, axis_law::spring_damper>;
  static constexpr bool has_friction = std::is_same_v<Law, axis_law::friction>;
  static constexpr bool has_input = has_spring_damper || has_friction;

  using params = detail::revolute_params<Axis, Law>;

  Revolute() : Revolute(params{}) {}
  explicit Revolute(params p) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), "Revolute", p.n);
    if constexpr (has_spring_damper) law_ = detail::make_axis_law<Law>(name.view(), "Revolute", p, p.phi0);
    if constexpr (has_friction) law_ = detail::make_axis_law<Law>(name.view(), "Revolute", p, 0.0);
  }

  /// The generalised force of the axis law on φ: −c·(φ − φ0) − d·φ̇, or
  /// −d·φ̇ − F_c·tanh(φ̇ / v_s).
  template <class T>
  [[nodiscard]] T generalized_force(const T&, const joint_state<T>& x, int q) const {
    return detail::axis_law_force<Law>(law_, x.q(q), x.qd(q));
  }

  [[nodiscard]] const Vec3d& n() const { return n_; }

  /// The axis law's potential energy at q (a spring-damper's ½·c·(q − q₀)², else 0).
  template <class T>
  [[nodiscard]] T elastic_energy(const T& q) const {
    return detail::axis_law_potential<Law>(law_, q);
  }

  static constexpr auto phi = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto R_rel = internal_<2, 1, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> n{n_, "n"};
    return boost::hana::make_tuple(
        orientation_eq(R_rel, n * transpose(n) + (identity{} - n * transpose(n)) * cos(phi) - tilde(n) * sin(phi)),
        eq(r_<0>, r_<1>),                          //
        orientation_eq(R_<1>, R_rel * R_<0>),      //
        eq(F_<1>, -(R_rel * F_<0>)),               //
        eq(M_<1>, -(R_rel * M_<0>)),               //
        axis_equation(n));
  }

  template <class T>
  [[nodiscard]] Mat3<T> relative_rotation(const T& q) const {
    return axis_rotation<T>(n_.cast<T>(), q);
  }
  template <class T>
  [[nodiscard]] wrench<T> flows_a_from_b(const wrench<T>& b, const T& q) const {
    const Mat3<T> Rt = relative_rotation(q).transpose();
    return {-(Rt * b.f), -(Rt * b.n)};
  }
  template <class T>
  [[nodiscard]] wrench<T> flows_b_from_a(const wrench<T>& a, const T& q) const {
    const Mat3<T> R = relative_rotation(q);
    return {-(R * a.f), -(R * a.n)};
  }

 private:
  auto axis_equation(const expr::param<Vec3d>& n) const {
    using namespace expr;
    if constexpr (has_input) return eq(dot(M_<1>, n), flange::detail::axis_law_resistance<Law>(law_, phi, "φ0"));
    else return eq(zero<shape::scalar>{}, dot(M_<1>, n));
  }

  Vec3d n_;
  detail::axis_law_values law_;
};

}  // namespace flange
