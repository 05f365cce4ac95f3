// Revolute: rotation about a fixed axis n (unit, in frame_a = frame_b coordinates).
//
//   R_rel = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//   r₁ = r₂                  F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₂ = −R_rel·M₁
//                            0  = M₂·n
//
// Frames 1, 2 are frame_a, frame_b; φ and R_rel are internal variables. R_rel
// is the transpose of the active Rodrigues matrix: frame_b is frame_a turned by
// +φ about n. Undriven, the joint transmits no torque about n.
//
// A drive (Modelica's useAxisFlange with a torque source, in one component):
// Revolute<"elbow", axis::z, axis_law::none, Tau>({.tau = τ}), or the factory
// revolute<"elbow", axis::z>(τ) that deduces Tau, takes a torque input τ about
// the axis: a constant, a callable τ(t) or τ(t, x) of the joint state (see
// joint_state), with no virtual call. τ > 0 turns frame_b toward +φ, and the
// last equation becomes
//
//   τ = −M₂·n          (with an axis law:  τ − (c·(φ − φ0) + d·φ̇) = −M₂·n)
//
// A joint without a drive (Tau = undriven, the default) has no input and no
// input arithmetic.
//
// Revolute<"elbow", axis::z> fixes the axis at compile time; Revolute<"elbow">
// takes it at construction.
//
// Motion (core/joint.hpp): nq = nv = 1, q = φ, v = φ̇. E = R_rel(σ·n, φ), the
// child origin stays at frame_a's (p = 0), S = (σ·n, 0), no bias; σ = −1 when
// the joint is connected frame_b toward the World (R_rel(n, φ)ᵀ = R_rel(−n, φ)).
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
//
// Revolute<"elbow", axis::z, axis_law::limited<>> stops the joint at a lower
// and an upper angle, with a compliant stop (Simbody's MobilityLinearStop,
// joints/axis_law.hpp): {.stop = {.lower = -2, .upper = 2, .stiffness = 1e4,
// .dissipation = 0.1}}. axis_law::limited<axis_law::friction> (or
// spring_damper) keeps that law and adds the stops.
#pragma once
#include <array>
#include <initializer_list>
#include <cmath>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/joints/axis.hpp"
#include "flange/joints/axis_law.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace diagnostic {
template <class F>
struct revolute_input_type_not_given {
  static_assert(always_false<F>,
                "flange: this Revolute's drive torque tau is a callable, but the Revolute's torque type was not "
                "given: write revolute<\"name\", axis::z>(f), or Revolute<\"name\", axis::z, axis_law::none, "
                "decltype(f)>({.tau = f})");
};
}  // namespace diagnostic

namespace detail {
template <class Tau>
using revolute_torque_slot = input_slot<Tau, diagnostic::revolute_input_type_not_given>;
template <class Axis, class Law, class Stop>
struct revolute_params {
  Vec3d n = Vec3d::UnitZ();
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <int I, class Stop>
struct revolute_params<axis::coordinate<I>, axis_law::none, Stop> {
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Stop>
struct revolute_params<Axis, axis_law::spring_damper, Stop> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  double c = 0;              ///< stiffness [N m/rad]
  double d = 0;              ///< damping [N m s/rad]
  double phi0 = 0;           ///< rest angle [rad]
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Stop>
struct revolute_params<Axis, axis_law::friction, Stop> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  double d = 0;              ///< viscous friction [N m s/rad]
  double f_c = 0;            ///< Coulomb friction torque [N m]
  double v_s = 1e-3;         ///< regularisation speed [rad/s]: tanh(φ̇ / v_s)
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};

/// The parameters of a driven joint: the same, and the torque input τ.
template <class Axis, class Law, class Tau, class Stop>
struct revolute_driven_params {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  revolute_torque_slot<Tau> tau{};  ///< the drive's torque about the axis [N m]
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <int I, class Tau, class Stop>
struct revolute_driven_params<axis::coordinate<I>, axis_law::none, Tau, Stop> {
  revolute_torque_slot<Tau> tau{};  ///< the drive's torque about the axis [N m]
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Tau, class Stop>
struct revolute_driven_params<Axis, axis_law::spring_damper, Tau, Stop> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  revolute_torque_slot<Tau> tau{};  ///< the drive's torque about the axis [N m]
  double c = 0;              ///< stiffness [N m/rad]
  double d = 0;              ///< damping [N m s/rad]
  double phi0 = 0;           ///< rest angle [rad]
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Tau, class Stop>
struct revolute_driven_params<Axis, axis_law::friction, Tau, Stop> {
  Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  revolute_torque_slot<Tau> tau{};  ///< the drive's torque about the axis [N m]
  double d = 0;              ///< viscous friction [N m s/rad]
  double f_c = 0;            ///< Coulomb friction torque [N m]
  double v_s = 1e-3;         ///< regularisation speed [rad/s]: tanh(φ̇ / v_s)
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};

/// A revolute joint's motion (core/joint.hpp): E = R_rel(σ·n, φ), S = (σ·n, 0).
/// A compile-time axis is not stored: σ·e_I is a constant of the type, so
/// the compiler folds it into every product.
template <class T, class Axis, int Dir>
struct revolute_motion : motion_base<T> {
  static constexpr int nv = 1;
  using rotation_t = std::conditional_t<Axis::fixed, coordinate_rotation<T, (Axis::fixed ? Axis::index : 0)>, Mat3<T>>;
  using axis_t = decltype(axis::signed_unit<T, Axis, Dir>(Vec3d{}));
  struct no_axis {};
  rotation_t E;
  [[no_unique_address]] std::conditional_t<Axis::fixed, no_axis, axis_t> n_;  ///< σ·n, for a run-time axis
  zero_vec<T> p{};
  /// σ·n.
  FLANGE_INLINE axis_t axis() const {
    if constexpr (Axis::fixed) return axial<T, Axis::index>(T(Dir));
    else return n_;
  }
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else if constexpr (Axis::fixed) return axial<T, Axis::index>(Dir > 0 ? v[0] : -v[0]);
    else return v[0] * n_;
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 1> project(const N& torque, const F&) const {
    if constexpr (Axis::fixed) {
      const T x = torque.template get<Axis::index>();
      return {Dir > 0 ? x : -x};
    } else {
      return {value_of<T>(dot(n_, torque))};
    }
  }
  template <int K>
  FLANGE_INLINE motion_pair<axis_t, zero_vec<T>> col() const {
    return {axis(), {}};
  }
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any, class Law = axis_law::none, class Tau = undriven>
class Revolute {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Revolute";
  static constexpr role kind = role::joint;
  using axis_type = Axis;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"φ", expr::var_kind::scalar}, {"R_rel", expr::var_kind::rot}}};
  static constexpr bool has_spring_damper = std::is_same_v<detail::inner_law<Law>, axis_law::spring_damper>;
  static constexpr bool has_friction = std::is_same_v<detail::inner_law<Law>, axis_law::friction>;
  static constexpr bool has_stops = detail::law_parts<Law>::stops;
  static constexpr bool has_law = has_spring_damper || has_friction || has_stops;
  static constexpr bool driven = !std::is_same_v<Tau, undriven>;

  // ---------------------------------------------------------- motion
  static constexpr int nq = 1, nv = 1;
  static constexpr bool reversible = true;
  /// Its axis is fixed in its link: S does not depend on q (core/joint.hpp).
  static constexpr bool fixed_subspace = true;
  /// Its generalized force reads other joints' states only through a drive
  /// τ(t, x) (core/joint.hpp).
  static constexpr bool force_reads_state = driven && input_reads_state<Tau>;
  /// It turns about its axis: a coordinate axis makes it planar about that axis.
  static constexpr int planar_normal() { return Axis::fixed ? Axis::index : -1; }
  static constexpr bool moves_in_plane(int k) { return Axis::fixed && Axis::index == k; }
  /// Closing a loop, it leaves the rotation about n free.
  static constexpr cut_freedom as_cut{.rotations = 1, .translations = 0};

  using params = std::conditional_t<driven,
                                    detail::revolute_driven_params<Axis, detail::inner_law<Law>, Tau, detail::stop_field<Law>>,
                                    detail::revolute_params<Axis, detail::inner_law<Law>, detail::stop_field<Law>>>;

  /// Revolute<…>{} and Revolute<…>({}): every parameter defaulted (all_defaults).
  Revolute() : Revolute(params{}) {}
  Revolute(std::initializer_list<all_defaults>) : Revolute(params{}) {}
  explicit Revolute(params p) : tau_(take_tau(p)) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), "Revolute", p.n);
    if constexpr (std::is_arithmetic_v<Tau>) detail::require_finite(name.view(), "Revolute", "tau", tau_);
    if constexpr (has_spring_damper) law_ = detail::make_axis_law<Law>(name.view(), "Revolute", p, p.phi0);
    else if constexpr (has_law) law_ = detail::make_axis_law<Law>(name.view(), "Revolute", p, 0.0);
  }

  [[nodiscard]] const Vec3d& n() const { return n_; }
  [[nodiscard]] const Tau& tau() const { return tau_; }

  [[nodiscard]] static std::array<double, 1> neutral() { return {0.0}; }

  /// The motion at φ = q[0]. Without NeedRotation the sine and cosine of a
  /// coordinate-axis rotation are not computed (nothing will apply it).
  template <class T, int Dir, bool NeedRotation>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    if constexpr (NeedRotation || !Axis::fixed) return motion<T, Dir>(q, cos_sin_of(q[0]));
    else return motion<T, Dir>(q, cos_sin<T>{T(1), T(0)});  // never applied (links.hpp: need_rotation)
  }
  /// Its motion turns by one angle, φ = q[0] (core/joint.hpp): the same motion
  /// with cos φ and sin φ given, which links.hpp computes for all links at once.
  static constexpr int angle_coordinate = 0;
  template <class T, int Dir>
  [[nodiscard]] FLANGE_INLINE auto motion(const T*, const cos_sin<T>& a) const {
    if constexpr (Axis::fixed) {
      return coordinate_motion<T, Axis, Dir>(a);
    } else {
      detail::revolute_motion<T, Axis, Dir> m;
      m.n_ = axis::signed_unit<T, Axis, Dir>(n_);
      m.E = axis_rotation<T>(m.n_.dense(), a);
      return m;
    }
  }
  /// A run-time axis lets its link compute in coordinates turned so that n
  /// is z (dynamics/axis_frames.hpp, core/joint.hpp): there the motion is
  /// that of a Revolute about z, a 2-D rotation and S = (±e_z, 0). Its angle
  /// may be φ = q[0] plus a constant turn of the frame about the axis
  /// (axis_frames.hpp), added by the caller.
  static constexpr bool axis_frame = !Axis::fixed;
  template <class T, int Dir, bool NeedRotation>
    requires(!Axis::fixed)
  [[nodiscard]] FLANGE_INLINE auto motion_in_axis_frame(const T* q) const {
    if constexpr (NeedRotation) return motion_in_axis_frame<T, Dir>(q, cos_sin_of(q[0]));
    else return motion_in_axis_frame<T, Dir>(q, cos_sin<T>{T(1), T(0)});
  }
  template <class T, int Dir>
    requires(!Axis::fixed)
  [[nodiscard]] FLANGE_INLINE auto motion_in_axis_frame(const T*, const cos_sin<T>& a) const {
    return coordinate_motion<T, axis::z, Dir>(a);
  }
  template <class T>
  void qdot(const T*, const T* v, T* qd) const {
    qd[0] = v[0];
  }
  /// As a cut joint: φ and φ̇ from frame_b's pose in frame_a (R rotates
  /// frame_a coordinates into frame_b's) and the relative angular velocity
  /// w (frame_a coordinates), the inverse of relative_pose on a closed loop.
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>&, const Vec3<T>& w, const Vec3<T>&, T* q, T* v) const {
    Vec3d e1, e2;
    complete_basis(n_, e1, e2);
    q[0] = turn_about<T>(n_, e1, R * e1.cast<T>());
    v[0] = n_.cast<T>().dot(w);
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> R = axis_rotation<T>(n_.cast<T>(), q[0]);
    set(0, q[0], v[0]);
    set(1, R, Mat3<T>(-tilde<T>(n_.cast<T>() * v[0]) * R));
  }
  /// The generalized force on φ: the drive's torque input at (t, x), and
  /// the axis law's −c·(φ − φ0) − d·φ̇, or −d·φ̇ − F_c·tanh(φ̇ / v_s).
  template <class T>
    requires(has_law || driven)
  void generalized_force(const T& t, const state_of<T> auto& x, const T* q, const T* v, T* tau) const {
    if constexpr (driven && has_law) tau[0] = eval_input(tau_, t, x) + detail::axis_law_force<Law>(law_, q[0], v[0]);
    else if constexpr (driven) tau[0] = eval_input(tau_, t, x);
    else tau[0] = detail::axis_law_force<Law>(law_, q[0], v[0]);
  }
  /// The axis law's potential energy at q (a spring-damper's ½·c·(φ − φ0)², else 0).
  template <class T>
  [[nodiscard]] T elastic_energy(const T* q) const {
    return detail::axis_law_potential<Law>(law_, q[0]);
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

 private:
  static Tau take_tau(params& p) {
    if constexpr (driven) return take_input(std::move(p.tau));
    else return {};
  }
  auto axis_equation(const expr::param<Vec3d>& n) const {
    using namespace expr;
    if constexpr (driven) {
      const input_node<Tau, shape::scalar> tau{{}, &tau_, "τ"};
      if constexpr (has_law) return eq(tau - flange::detail::axis_law_resistance<Law>(law_, phi, "φ0"), -dot(M_<1>, n));
      else return eq(tau, -dot(M_<1>, n));
    } else if constexpr (has_law) {
      return eq(dot(M_<1>, n), flange::detail::axis_law_resistance<Law>(law_, phi, "φ0"));
    } else {
      return eq(zero<shape::scalar>{}, dot(M_<1>, n));
    }
  }

  template <class T, class A, int Dir>
  FLANGE_INLINE static detail::revolute_motion<T, A, Dir> coordinate_motion(const cos_sin<T>& a) {
    detail::revolute_motion<T, A, Dir> m;
    m.E.c = a.c;
    m.E.s = Dir > 0 ? a.s : -a.s;
    return m;
  }

  Vec3d n_;
  [[no_unique_address]] Tau tau_;
  detail::axis_law_values law_;
};

}  // namespace flange

namespace flange {
/// A driven Revolute with the torque input's type deduced:
/// revolute<"elbow", axis::z>(τ) or revolute<"elbow">(τ, n).
template <fixed_string Name, class Axis, class Tau>
  requires Axis::fixed
auto revolute(Tau tau) {
  return Revolute<Name, Axis, axis_law::none, Tau>({std::move(tau)});
}
template <fixed_string Name, class Tau>
auto revolute(Tau tau, const Vec3d& n) {
  return Revolute<Name, axis::any, axis_law::none, Tau>({n, std::move(tau)});
}
}  // namespace flange
