// Prismatic: translation s along a fixed axis n (unit, frame_a coordinates),
// driven by the axial force input f.
//
//   r₂ = r₁ + s·R₁'·n        F₂ = −F₁
//   R₂ = R₁                  M₂ = −M₁ + s·n × F₁
//                            f  = −F₂·n
//
// Frames 1, 2 are frame_a, frame_b; s is the internal variable. f > 0 pushes
// frame_b along +n. f is a constant, a callable f(t), or f(t, x) of the joint
// state x (see joint_state).
//
// Prismatic<"rail", axis::x, double, axis_law::spring_damper> or
// axis_law::friction adds a law along the axis (joints/axis_law.hpp); the last
// equation becomes  f − (c·(s − s0) + d·ṡ) = −F₂·n, or
// f − (d·ṡ + F_c·tanh(ṡ / v_s)) = −F₂·n.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/components/component.hpp"
#include "flange/components/frame_kinematics.hpp"
#include "flange/joints/axis.hpp"
#include "flange/joints/axis_law.hpp"
#include "flange/joints/revolute.hpp"

namespace flange {

namespace detail {
// The parameters: the axis n (a run-time axis only), the force input f, and
// the axis law's numbers.
template <class Axis, class Force, class Law>
struct prismatic_params {
  Vec3d n = Vec3d::UnitX();
  Force f{};
};
template <int I, class Force>
struct prismatic_params<axis::coordinate<I>, Force, axis_law::none> {
  Force f{};
};
template <class Axis, class Force>
struct prismatic_params<Axis, Force, axis_law::spring_damper> {
  Vec3d n = Vec3d::UnitX();  ///< ignored for a compile-time axis
  Force f{};
  double c = 0;   ///< stiffness [N/m]
  double d = 0;   ///< damping [N s/m]
  double s0 = 0;  ///< rest position [m]
};
template <class Axis, class Force>
struct prismatic_params<Axis, Force, axis_law::friction> {
  Vec3d n = Vec3d::UnitX();  ///< ignored for a compile-time axis
  Force f{};
  double d = 0;       ///< viscous friction [N s/m]
  double f_c = 0;     ///< Coulomb friction force [N]
  double v_s = 1e-3;  ///< regularisation speed [m/s]: tanh(ṡ / v_s)
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any, class Force = double, class Law = axis_law::none>
class Prismatic {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Prismatic";
  static constexpr role kind = role::joint;
  static constexpr joint_type type = joint_type::prismatic;
  using axis_type = Axis;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 1> internals{{{"s", expr::var_kind::scalar}}};
  static constexpr bool has_input = true;

  static constexpr bool has_law = !std::is_same_v<Law, axis_law::none>;
  using params = detail::prismatic_params<Axis, Force, Law>;

  explicit Prismatic(params p) : f_(std::move(p.f)) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), "Prismatic", p.n);
    if constexpr (std::is_arithmetic_v<Force>) detail::require_finite(name.view(), "Prismatic", "f", f_);
    if constexpr (std::is_same_v<Law, axis_law::spring_damper>)
      law_ = detail::make_axis_law<Law>(name.view(), "Prismatic", p, p.s0);
    else if constexpr (has_law) law_ = detail::make_axis_law<Law>(name.view(), "Prismatic", p, 0.0);
  }

  [[nodiscard]] const Vec3d& n() const { return n_; }

  /// The axis law's potential energy at q (a spring-damper's ½·c·(q − q₀)², else 0).
  template <class T>
  [[nodiscard]] T elastic_energy(const T& q) const {
    return detail::axis_law_potential<Law>(law_, q);
  }
  [[nodiscard]] const Force& f() const { return f_; }

  /// The generalised force on s: the axial force input at (t, x), plus the
  /// axis law's force (joints/axis_law.hpp).
  template <class T>
  [[nodiscard]] T generalized_force(const T& t, const joint_state<T>& x, int q) const {
    if constexpr (has_law) return eval_input(f_, t, x) + detail::axis_law_force<Law>(law_, x.q(q), x.qd(q));
    else return eval_input(f_, t, x);
  }

  static constexpr auto s = internal_<2, 0, expr::var_kind::scalar>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> n{n_, "n"};
    return boost::hana::make_tuple(eq(r_<1>, r_<0> + s * transpose(R_<0>) * n),  //
                                   orientation_eq(R_<1>, R_<0>),                    //
                                   eq(F_<1>, -F_<0>),                               //
                                   eq(M_<1>, -M_<0> + s * cross(n, F_<0>)),         //
                                   axis_equation(n));
  }

  template <class T>
  [[nodiscard]] wrench<T> flows_a_from_b(const wrench<T>& b, const T& q) const {
    const Vec3<T> Fa = -b.f;
    return {Fa, (q * n_.cast<T>()).cross(Fa) - b.n};
  }
  template <class T>
  [[nodiscard]] wrench<T> flows_b_from_a(const wrench<T>& a, const T& q) const {
    return {-a.f, -a.n + (q * n_.cast<T>()).cross(a.f)};
  }

 private:
  auto axis_equation(const expr::param<Vec3d>& n) const {
    using namespace expr;
    const input_node<Force, shape::scalar> f{{}, &f_, "f"};
    if constexpr (has_law) return eq(f - flange::detail::axis_law_resistance<Law>(law_, s, "s0"), -dot(F_<1>, n));
    else return eq(f, -dot(F_<1>, n));
  }

  Vec3d n_;
  Force f_;
  detail::axis_law_values law_;
};

}  // namespace flange

namespace flange {
/// Prismatic<Name, Axis, F> with the force input's type deduced:
/// prismatic<"rail", axis::x>(fn) or prismatic<"rail">(fn, n).
template <fixed_string Name, class Axis, class Force>
  requires Axis::fixed
auto prismatic(Force f) {
  return Prismatic<Name, Axis, Force>({std::move(f)});
}
template <fixed_string Name, class Force>
auto prismatic(Force f, const Vec3d& n) {
  return Prismatic<Name, axis::any, Force>({n, std::move(f)});
}
}  // namespace flange
