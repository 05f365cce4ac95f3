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
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/components/component.hpp"
#include "flange/components/frame_kinematics.hpp"
#include "flange/joints/axis.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

enum class joint_type { revolute, prismatic };

namespace detail {
template <class Axis>
struct axis_params {
  Vec3d n = Vec3d::UnitZ();
};
template <int I>
struct axis_params<axis::coordinate<I>> {};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any>
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
  static constexpr bool has_input = false;

  using params = detail::axis_params<Axis>;

  Revolute() : Revolute(params{}) {}
  explicit Revolute(params p) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), "Revolute", p.n);
  }

  [[nodiscard]] const Vec3d& n() const { return n_; }

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
        eq(zero<shape::scalar>{}, dot(M_<1>, n)));
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
  Vec3d n_;
};

}  // namespace flange
