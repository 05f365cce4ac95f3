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
// f − (d·ṡ + F_c·tanh(ṡ / v_s)) = −F₂·n. axis_law::limited<Law> adds a
// compliant stop at each bound of s (`.stop = {.lower, .upper, .stiffness,
// .dissipation}`, joints/axis_law.hpp).
//
// Motion (core/joint.hpp): nq = nv = 1, q = s, v = ṡ. No rotation (E = 1),
// the child origin at p = σ·s·n, S = (0, σ·n), no bias; σ = −1 when the joint
// is connected frame_b toward the World.
#pragma once
#include <array>
#include <initializer_list>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/joints/axis.hpp"
#include "flange/joints/axis_law.hpp"

namespace flange {

namespace diagnostic {
template <class F>
struct prismatic_input_type_not_given {
  static_assert(always_false<F>,
                "flange: this Prismatic's force f is a callable, but the Prismatic's force type was not given: "
                "write prismatic<\"name\", axis::x>(f), or Prismatic<\"name\", axis::x, decltype(f)>({.f = f})");
};
}  // namespace diagnostic

namespace detail {
template <class Force>
using prismatic_force_slot = input_slot<Force, diagnostic::prismatic_input_type_not_given>;
// The parameters: the axis n (a run-time axis only), the force input f, and
// the axis law's numbers.
template <class Axis, class Force, class Law, class Stop>
struct prismatic_params {
  Vec3d n = Vec3d::UnitX();
  prismatic_force_slot<Force> f{};
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <int I, class Force, class Stop>
struct prismatic_params<axis::coordinate<I>, Force, axis_law::none, Stop> {
  prismatic_force_slot<Force> f{};
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Force, class Stop>
struct prismatic_params<Axis, Force, axis_law::spring_damper, Stop> {
  Vec3d n = Vec3d::UnitX();  ///< ignored for a compile-time axis
  prismatic_force_slot<Force> f{};
  double c = 0;   ///< stiffness [N/m]
  double d = 0;   ///< damping [N s/m]
  double s0 = 0;  ///< rest position [m]
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};
template <class Axis, class Force, class Stop>
struct prismatic_params<Axis, Force, axis_law::friction, Stop> {
  Vec3d n = Vec3d::UnitX();  ///< ignored for a compile-time axis
  prismatic_force_slot<Force> f{};
  double d = 0;       ///< viscous friction [N s/m]
  double f_c = 0;     ///< Coulomb friction force [N]
  double v_s = 1e-3;  ///< regularisation speed [m/s]: tanh(ṡ / v_s)
  [[no_unique_address]] Stop stop{};  ///< the stops, with axis_law::limited
};

/// A prismatic joint's motion (core/joint.hpp): E = 1, p = σ·s·n, S = (0, σ·n).
/// A compile-time axis is not stored (see revolute_motion).
template <class T, class Axis, int Dir>
struct prismatic_motion : motion_base<T> {
  static constexpr int nv = 1;
  using axis_t = decltype(axis::signed_unit<T, Axis, Dir>(Vec3d{}));
  struct no_axis {};
  identity_rotation E;
  [[no_unique_address]] std::conditional_t<Axis::fixed, no_axis, axis_t> n_;  ///< σ·n, for a run-time axis
  axis_t p;  ///< σ·s·n
  FLANGE_INLINE axis_t axis() const {
    if constexpr (Axis::fixed) return axial<T, Axis::index>(T(Dir));
    else return n_;
  }
  template <class V>
  FLANGE_INLINE zero_vec<T> w(const V&) const {
    return {};
  }
  template <class V>
  FLANGE_INLINE auto pd(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else if constexpr (Axis::fixed) return axial<T, Axis::index>(Dir > 0 ? v[0] : -v[0]);
    else return v[0] * n_;
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 1> project(const N&, const F& force) const {
    if constexpr (Axis::fixed) {
      const T x = force.template get<Axis::index>();
      return {Dir > 0 ? x : -x};
    } else {
      return {value_of<T>(dot(n_, force))};
    }
  }
  template <int K>
  FLANGE_INLINE motion_pair<zero_vec<T>, axis_t> col() const {
    return {{}, axis()};
  }
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any, class Force = double, class Law = axis_law::none>
class Prismatic {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Prismatic";
  static constexpr role kind = role::joint;
  using axis_type = Axis;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 1> internals{{{"s", expr::var_kind::scalar}}};
  static constexpr bool has_law = !std::is_same_v<Law, axis_law::none>;

  // ---------------------------------------------------------- motion
  static constexpr int nq = 1, nv = 1;
  static constexpr bool reversible = true;
  /// Its axis is fixed in its link: S does not depend on q (core/joint.hpp).
  static constexpr bool fixed_subspace = true;
  /// Its generalized force reads other joints' states only through a force
  /// input f(t, x) (core/joint.hpp).
  static constexpr bool force_reads_state = input_reads_state<Force>;
  /// It does not turn; it slides in the plane normal to k when its axis is another coordinate axis.
  static constexpr int planar_normal() { return -2; }
  static constexpr bool moves_in_plane(int k) { return Axis::fixed && Axis::index != k; }
  /// Closing a loop, it leaves the translation along n free.
  static constexpr cut_freedom as_cut{.rotations = 0, .translations = 1};

  using params = detail::prismatic_params<Axis, Force, detail::inner_law<Law>, detail::stop_field<Law>>;

  /// Prismatic<…>{} and Prismatic<…>({}): every parameter defaulted (all_defaults).
  Prismatic() : Prismatic(params{}) {}
  Prismatic(std::initializer_list<all_defaults>) : Prismatic(params{}) {}
  explicit Prismatic(params p) : f_(take_input(std::move(p.f))) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), "Prismatic", p.n);
    if constexpr (std::is_arithmetic_v<Force>) detail::require_finite(name.view(), "Prismatic", "f", f_);
    if constexpr (std::is_same_v<detail::inner_law<Law>, axis_law::spring_damper>)
      law_ = detail::make_axis_law<Law>(name.view(), "Prismatic", p, p.s0);
    else if constexpr (has_law) law_ = detail::make_axis_law<Law>(name.view(), "Prismatic", p, 0.0);
  }

  [[nodiscard]] const Vec3d& n() const { return n_; }
  [[nodiscard]] const Force& f() const { return f_; }

  [[nodiscard]] static std::array<double, 1> neutral() { return {0.0}; }

  template <class T, int Dir, bool>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    detail::prismatic_motion<T, Axis, Dir> m;
    if constexpr (Axis::fixed) {
      m.p = axial<T, Axis::index>(Dir > 0 ? q[0] : -q[0]);
    } else {
      m.n_ = axis::signed_unit<T, Axis, Dir>(n_);
      m.p = q[0] * m.n_;
    }
    return m;
  }
  template <class T>
  void qdot(const T*, const T* v, T* qd) const {
    qd[0] = v[0];
  }
  /// As a cut joint: s and ṡ from frame_b's origin p in frame_a and its
  /// rate (frame_a coordinates), the inverse of relative_pose on a closed loop.
  template <class T>
  void cut_state(const Mat3<T>&, const Vec3<T>& p, const Vec3<T>&, const Vec3<T>& pd, T* q, T* v) const {
    q[0] = n_.cast<T>().dot(p);
    v[0] = n_.cast<T>().dot(pd);
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    set(0, q[0], v[0]);
  }
  /// The generalized force on s: the axial force input at (t, x), plus the
  /// axis law's force (joints/axis_law.hpp).
  template <class T>
  void generalized_force(const T& t, const state_of<T> auto& x, const T* q, const T* v, T* tau) const {
    if constexpr (has_law) tau[0] = eval_input(f_, t, x) + detail::axis_law_force<Law>(law_, q[0], v[0]);
    else tau[0] = eval_input(f_, t, x);
  }
  /// The axis law's potential energy at q (a spring-damper's ½·c·(s − s0)², else 0).
  template <class T>
  [[nodiscard]] T elastic_energy(const T* q) const {
    return detail::axis_law_potential<Law>(law_, q[0]);
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
