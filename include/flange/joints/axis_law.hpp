// Laws acting along a joint's axis, like Modelica's 1-D flange elements
// (Rotational / Translational SpringDamper, and bearing friction) attached to
// a joint's axis. With q the joint coordinate (φ or s), the law's generalised
// force on q is τ, and the joint's axis equation carries −τ:
//
//   axis_law::none           τ = 0                              (the paper's joints)
//   axis_law::spring_damper  τ = −c·(q − q₀) − d·q̇
//   axis_law::friction       τ = −d·q̇ − F_c·tanh(q̇ / v_s)      viscous plus Coulomb
//
// Coulomb friction is regularised (smooth): tanh over a speed v_s, so the
// stepper sees a smooth right-hand side and no stick-slip events. Below
// |q̇| ≈ v_s the joint creeps instead of sticking; choose v_s well below the
// speeds that matter. A joint without a law has none of this arithmetic.
#pragma once
#include <cmath>
#include <string_view>

#include "flange/core/component.hpp"

namespace flange {

namespace axis_law {
struct none {};           ///< no force along the axis
struct spring_damper {};  ///< linear spring and damper along the axis
struct friction {};       ///< viscous plus regularised Coulomb friction along the axis
}  // namespace axis_law

namespace detail {

/// The numbers of an axis law (which ones matter depends on the law).
struct axis_law_values {
  double c = 0, d = 0, q0 = 0, fc = 0, inv_vs = 0;
};

/// Validates and stores a law's parameters; `q0` is the rest position
/// (φ0 or s0) of a spring-damper. Messages name the joint and the value.
template <class Law, class P>
axis_law_values make_axis_law(std::string_view name, std::string_view kind, const P& p, double q0) {
  axis_law_values v;
  if constexpr (std::is_same_v<Law, axis_law::spring_damper>) {
    for (auto [what, x] : {std::pair{"c (stiffness)", p.c}, {"d (damping)", p.d}, {"rest position", q0}})
      require_finite(name, kind, what, x);
    if (p.c < 0 || p.d < 0)
      throw parameter_error(concat(kind, " \"", name, "\": spring-damper c = ", p.c, ", d = ", p.d,
                                   "; stiffness and damping must not be negative"));
    v.c = p.c;
    v.d = p.d;
    v.q0 = q0;
  } else if constexpr (std::is_same_v<Law, axis_law::friction>) {
    for (auto [what, x] : {std::pair{"d (viscous friction)", p.d}, {"f_c (Coulomb friction)", p.f_c}, {"v_s", p.v_s}})
      require_finite(name, kind, what, x);
    if (p.d < 0 || p.f_c < 0)
      throw parameter_error(concat(kind, " \"", name, "\": friction d = ", p.d, ", f_c = ", p.f_c,
                                   "; friction coefficients must not be negative"));
    if (!(p.v_s > 0))
      throw parameter_error(concat(kind, " \"", name, "\": friction v_s = ", p.v_s,
                                   " must be positive (it is the speed over which tanh regularises Coulomb friction)"));
    v.d = p.d;
    v.fc = p.f_c;
    v.inv_vs = 1 / p.v_s;
  }
  return v;
}

/// τ, the law's generalised force on q.
template <class Law, class T>
T axis_law_force(const axis_law_values& v, const T& q, const T& qd) {
  if constexpr (std::is_same_v<Law, axis_law::spring_damper>) {
    return -T(v.c) * (q - T(v.q0)) - T(v.d) * qd;
  } else if constexpr (std::is_same_v<Law, axis_law::friction>) {
    using std::tanh;
    return -T(v.d) * qd - T(v.fc) * tanh(qd * T(v.inv_vs));
  } else {
    (void)v, (void)q, (void)qd;
    return T(0);
  }
}

/// The law's potential energy: ½·c·(q − q₀)² for a spring-damper, else 0.
template <class Law, class T>
T axis_law_potential(const axis_law_values& v, const T& q) {
  if constexpr (std::is_same_v<Law, axis_law::spring_damper>) {
    const T stretch = q - T(v.q0);
    return T(0.5 * v.c) * stretch * stretch;
  } else {
    (void)v, (void)q;
    return T(0);
  }
}

/// −τ as an expression of the joint variable q, for the axis equation.
template <class Law, class Q>
auto axis_law_resistance(const axis_law_values& v, Q q, const char* q0_name) {
  using namespace expr;
  if constexpr (std::is_same_v<Law, axis_law::spring_damper>)
    return param<double>{v.c, "c"} * (q - param<double>{v.q0, q0_name}) + param<double>{v.d, "d"} * der(q);
  else
    return param<double>{v.d, "d"} * der(q) +
           param<double>{v.fc, "F_c"} * tanh(der(q) * param<double>{v.inv_vs, "1/v_s"});
}

}  // namespace detail
}  // namespace flange
