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
//
// axis_law::limited<Law> is Law plus a compliant stop at each bound of q
// (the joint's `.stop = {.lower, .upper, .stiffness, .dissipation}`), as
// Simbody's Force::MobilityLinearStop: with k the stiffness and d the
// dissipation coefficient [s/m or s/rad],
//
//   τ_stop = 0                             lower ≤ q ≤ upper
//          = min(0, −k·x·(1 + d·q̇))       q > upper,  x = q − upper
//          = max(0, −k·x·(1 − d·q̇))       q < lower,  x = q − lower
//
// so the stop pushes, never pulls, and its damping is zero at first touch
// (Hunt–Crossley-like). Its potential energy is ½·k·x². The force is
// continuous, its slope is not at a bound: error-controlled steppers take a
// short step there. An infinite bound has no stop.
#pragma once
#include <cmath>
#include <limits>
#include <string_view>

#include "flange/core/component.hpp"

namespace flange {

namespace axis_law {
struct none {};           ///< no force along the axis
struct spring_damper {};  ///< linear spring and damper along the axis
struct friction {};       ///< viscous plus regularised Coulomb friction along the axis
/// Law, and a compliant stop at a lower and an upper bound of the coordinate.
template <class Law = none>
struct limited {};
}  // namespace axis_law

/// A joint's stops (axis_law::limited): the bounds of its coordinate, and the
/// stops' stiffness k [N/m or N m/rad] and dissipation d [s/m or s/rad].
struct axis_stop {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  double stiffness = 0;
  double dissipation = 0;
};

namespace detail {

/// Law without its stops, and whether it has them.
template <class Law>
struct law_parts {
  using inner = Law;
  static constexpr bool stops = false;
};
template <class Law>
struct law_parts<axis_law::limited<Law>> {
  static_assert(!law_parts<Law>::stops, "flange: axis_law::limited<axis_law::limited<…>>: a joint has one pair of stops");
  using inner = Law;
  static constexpr bool stops = true;
};
template <class Law>
using inner_law = typename law_parts<Law>::inner;

/// The joint parameters' `.stop` field: the stops of axis_law::limited, else empty.
struct no_stop {};
template <class Law>
using stop_field = std::conditional_t<law_parts<Law>::stops, axis_stop, no_stop>;

/// The numbers of an axis law (which ones matter depends on the law).
struct axis_law_values {
  double c = 0, d = 0, q0 = 0, fc = 0, inv_vs = 0;
  double lower = 0, upper = 0, k_stop = 0, d_stop = 0;
};

/// A stop's generalized force on q (Simbody's MobilityLinearStop, above).
template <class T>
T stop_force(const axis_law_values& v, const T& q, const T& qd) {
  if (q > T(v.upper)) {
    const T f = -T(v.k_stop) * (q - T(v.upper)) * (T(1) + T(v.d_stop) * qd);
    return f < T(0) ? f : T(0);
  }
  if (q < T(v.lower)) {
    const T f = -T(v.k_stop) * (q - T(v.lower)) * (T(1) - T(v.d_stop) * qd);
    return f > T(0) ? f : T(0);
  }
  return T(0);
}

/// A stop's potential energy ½·k·x², x the distance past a bound.
template <class T>
T stop_potential(const axis_law_values& v, const T& q) {
  const T x = q > T(v.upper) ? q - T(v.upper) : q < T(v.lower) ? q - T(v.lower) : T(0);
  return T(0.5 * v.k_stop) * x * x;
}

/// The stop force as a function of (q, q̇) in the residual: printed stop(q, der(q)).
struct stop_law {
  axis_law_values v;
  static constexpr const char* name = "stop";
  template <class T>
  T operator()(const T& q, const T& qd) const {
    return stop_force(v, q, qd);
  }
};

/// Validates and stores a law's parameters; `q0` is the rest position
/// (φ0 or s0) of a spring-damper. Messages name the joint and the value.
template <class Law, class P>
axis_law_values make_axis_law(std::string_view name, std::string_view kind, const P& p, double q0) {
  if constexpr (law_parts<Law>::stops) {
    axis_law_values v = make_axis_law<inner_law<Law>>(name, kind, p, q0);
    const axis_stop& s = p.stop;
    for (auto [what, x] : {std::pair{"stop stiffness", s.stiffness}, {"stop dissipation", s.dissipation}})
      require_finite(name, kind, what, x);
    if (std::isnan(s.lower) || std::isnan(s.upper))
      throw parameter_error(concat(kind, " \"", name, "\": stop bounds lower = ", s.lower, ", upper = ", s.upper,
                                   "; a bound is a number (an infinite one has no stop)"));
    if (s.lower > s.upper)
      throw parameter_error(concat(kind, " \"", name, "\": stop lower = ", s.lower, " is above upper = ", s.upper));
    if (s.stiffness < 0 || s.dissipation < 0)
      throw parameter_error(concat(kind, " \"", name, "\": stop stiffness = ", s.stiffness,
                                   ", dissipation = ", s.dissipation, "; they must not be negative"));
    v.lower = s.lower;
    v.upper = s.upper;
    v.k_stop = s.stiffness;
    v.d_stop = s.dissipation;
    return v;
  }
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
  if constexpr (law_parts<Law>::stops) {
    if constexpr (std::is_same_v<inner_law<Law>, axis_law::none>) return stop_force(v, q, qd);
    else return axis_law_force<inner_law<Law>>(v, q, qd) + stop_force(v, q, qd);
  } else if constexpr (std::is_same_v<Law, axis_law::spring_damper>) {
    return -T(v.c) * (q - T(v.q0)) - T(v.d) * qd;
  } else if constexpr (std::is_same_v<Law, axis_law::friction>) {
    using std::tanh;
    return -T(v.d) * qd - T(v.fc) * tanh(qd * T(v.inv_vs));
  } else {
    (void)v, (void)q, (void)qd;
    return T(0);
  }
}

/// The law's potential energy: ½·c·(q − q₀)² for a spring-damper, ½·k·x²
/// past a stop, else 0.
template <class Law, class T>
T axis_law_potential(const axis_law_values& v, const T& q) {
  if constexpr (law_parts<Law>::stops) {
    return axis_law_potential<inner_law<Law>>(v, q) + stop_potential(v, q);
  } else if constexpr (std::is_same_v<Law, axis_law::spring_damper>) {
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
  if constexpr (law_parts<Law>::stops) {
    auto stop = -call(stop_law{v}, q, der(q));
    if constexpr (std::is_same_v<inner_law<Law>, axis_law::none>) return stop;
    else return axis_law_resistance<inner_law<Law>>(v, q, q0_name) + stop;
  } else if constexpr (std::is_same_v<Law, axis_law::spring_damper>)
    return param<double>{v.c, "c"} * (q - param<double>{v.q0, q0_name}) + param<double>{v.d, "d"} * der(q);
  else
    return param<double>{v.d, "d"} * der(q) +
           param<double>{v.fc, "F_c"} * tanh(der(q) * param<double>{v.inv_vs, "1/v_s"});
}

}  // namespace detail
}  // namespace flange
