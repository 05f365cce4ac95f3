// Spring, Damper, SpringDamper: a force along the line between two frames'
// origins, like Modelica's Forces.Spring, Damper and SpringDamper.
//
//   s² = (r₂ − r₁)·(r₂ − r₁)              s, the distance (s > 0)
//   f  = c·(s − s₀) + d·ṡ                 the tension (Spring: d = 0; Damper: c = 0)
//   s·F₁ = −f·R₁·(r₂ − r₁)               F₁ = −f·e in frame_a coordinates, e = (r₂ − r₁)/s
//   s·F₂ =  f·R₂·(r₂ − r₁)
//   M₁ = 0                   M₂ = 0
//
// Frames 1, 2 are frame_a, frame_b; s and f are internal variables. The
// equations are multiplied through by s, so the residual needs no square root
// and no division. A positive tension pulls the two frames together: the
// element pushes frame_a's side along +e and frame_b's side along −e. (As for
// every component, F and M are the flows into the element; what it exerts on
// the rest of the scene is their negative.)
//
// The force is undefined where the two origins meet (s = 0); a simulation
// that gets there throws simulation_error naming the element. A scene without
// line forces has none of this arithmetic, and no position pass.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"

namespace flange {

namespace line_law {
struct spring {};         ///< f = c·(s − s₀)
struct damper {};         ///< f = d·ṡ
struct spring_damper {};  ///< f = c·(s − s₀) + d·ṡ
}  // namespace line_law

namespace detail {
template <class Law>
struct line_force_params {
  double c = 0;   ///< stiffness [N/m]
  double s0 = 0;  ///< unstretched length [m]
  double d = 0;   ///< damping [N s/m]
};
template <>
struct line_force_params<line_law::spring> {
  double c = 0;
  double s0 = 0;
};
template <>
struct line_force_params<line_law::damper> {
  double d = 0;
};
}  // namespace detail

template <fixed_string Name, class Law>
class LineForce {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = std::is_same_v<Law, line_law::spring>   ? "Spring"
                                                : std::is_same_v<Law, line_law::damper> ? "Damper"
                                                                                        : "SpringDamper";
  static constexpr role kind = role::force;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"s", expr::var_kind::scalar}, {"f", expr::var_kind::scalar}}};
  /// Needs the frames' positions and velocities (a position pass in the dynamics).
  static constexpr bool needs_motion = true;
  /// Acts along a line between two frames, so both ends must be apart.
  static constexpr bool line_of_action = true;
  /// What it exerts: a force along its line, no torque.
  static constexpr bool exerts_force = true, exerts_torque = false;
  /// Its force reads its frames' motions alone, not the joint state.
  static constexpr bool reads_state = false;
  static constexpr bool has_spring = !std::is_same_v<Law, line_law::damper>;
  static constexpr bool has_damper = !std::is_same_v<Law, line_law::spring>;

  using params = detail::line_force_params<Law>;

  explicit LineForce(params p) {
    if constexpr (has_spring) {
      detail::require_finite(name.view(), type_name, "c (stiffness)", p.c);
      detail::require_finite(name.view(), type_name, "s0 (unstretched length)", p.s0);
      if (p.c < 0)
        throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": stiffness c = ", p.c, " is negative"));
      if (p.s0 < 0)
        throw parameter_error(
            detail::concat(type_name, " \"", name.view(), "\": unstretched length s0 = ", p.s0, " is negative"));
      c_ = p.c;
      s0_ = p.s0;
    }
    if constexpr (has_damper) {
      detail::require_finite(name.view(), type_name, "d (damping)", p.d);
      if (p.d < 0)
        throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": damping d = ", p.d, " is negative"));
      d_ = p.d;
    }
  }

  static constexpr auto s = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto f = internal_<2, 1, expr::var_kind::scalar>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    auto rel = r_<1> - r_<0>;
    return boost::hana::make_tuple(eq(s * s, dot(rel, rel)),  //
                                   eq(f, tension_expr()),    //
                                   eq(s * F_<0>, -(f * (R_<0> * rel))),
                                   eq(s * F_<1>, f * (R_<1> * rel)),  //
                                   eq(M_<0>, zero<shape::vec>{}),     //
                                   eq(M_<1>, zero<shape::vec>{}));
  }

  /// Length, its rate and the tension for the two frames' motion.
  template <class T>
  struct state {
    Vec3<T> e;  ///< unit vector from frame_a's origin to frame_b's, world coordinates
    T s, sd, f;
  };
  template <class T>
  [[nodiscard]] state<T> evaluate(const T& t, const frame_kinematics<T>& a, const frame_kinematics<T>& b) const {
    using std::sqrt;
    const Vec3<T> rel = b.r - a.r;
    const T s2 = rel.squaredNorm();
    if (!(s2 > T(0))) [[unlikely]]
      throw simulation_error(detail::concat(type_name, " \"", name.view(), "\": the two frames meet at t = ",
                                            static_cast<double>(t), ", where a line force has no direction"),
                             static_cast<double>(t));
    state<T> r;
    r.s = sqrt(s2);
    r.e = rel / r.s;
    r.sd = r.e.dot(b.v - a.v);
    r.f = T(0);
    if constexpr (has_spring) r.f = T(c_) * (r.s - T(s0_));
    if constexpr (has_damper) r.f += T(d_) * r.sd;
    return r;
  }

  /// What the element exerts on the rest of the scene at each of its frames:
  /// force and torque (about the frame's origin), world coordinates.
  template <class T>
  void wrenches(const T& t, const state_of<T> auto&, const frame_kinematics<T>* k, wrench<T>* on) const {
    const auto st = evaluate(t, k[0], k[1]);
    on[0] = {st.f * st.e, Vec3<T>::Zero()};
    on[1] = {-(st.f * st.e), Vec3<T>::Zero()};
  }

  /// The internal variables (s, f) and their rates, for the DAE vector.
  template <class T>
  [[nodiscard]] std::array<std::pair<T, T>, 2> internal_values(const T& t, const state_of<T> auto&,
                                                               const frame_kinematics<T>* k) const {
    const auto st = evaluate(t, k[0], k[1]);
    return {std::pair{st.s, st.sd}, std::pair{st.f, T(0)}};  // ḟ appears in no equation
  }

  /// The spring's potential energy ½·c·(s − s₀)², for recover()'s energy.
  template <class T>
  [[nodiscard]] T potential_energy(const T& t, const state_of<T> auto&, const frame_kinematics<T>* k) const {
    if constexpr (has_spring) {
      const T stretch = evaluate(t, k[0], k[1]).s - T(s0_);
      return T(0.5 * c_) * stretch * stretch;
    } else {
      return T(0);
    }
  }

 private:
  auto tension_expr() const {
    using namespace expr;
    if constexpr (has_spring && has_damper)
      return param<double>{c_, "c"} * (s - param<double>{s0_, "s0"}) + param<double>{d_, "d"} * der(s);
    else if constexpr (has_spring) return param<double>{c_, "c"} * (s - param<double>{s0_, "s0"});
    else return param<double>{d_, "d"} * der(s);
  }

  double c_ = 0, s0_ = 0, d_ = 0;
};

template <fixed_string Name>
using Spring = LineForce<Name, line_law::spring>;
template <fixed_string Name>
using Damper = LineForce<Name, line_law::damper>;
template <fixed_string Name>
using SpringDamper = LineForce<Name, line_law::spring_damper>;

}  // namespace flange
