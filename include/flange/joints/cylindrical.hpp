// Cylindrical: translation s along and rotation φ about one axis n (unit,
// frame_a coordinates), Modelica's Cylindrical (a Prismatic then a Revolute
// on the same axis).
//
//   R_rel = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//   r₂ = r₁ + s·R₁'·n        F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₂ = −R_rel·(M₁ − s·n × F₁)
//                            0  = F₂·n
//                            0  = M₂·n
//
// Frames 1, 2 are frame_a, frame_b; s, φ and R_rel are internal variables.
// Neither the force along n nor the torque about it is transmitted.
//
// Motion (core/joint.hpp): nq = nv = 2, q = (s, φ), v = (ṡ, φ̇). E = R_rel(σ·n,
// φ), p = σ·s·n, S = ((0, σ·n), (σ·n, 0)), no bias; σ = −1 when connected
// frame_b toward the World. Cylindrical<"c", axis::z> fixes the axis at
// compile time (2-D rotation arithmetic).
#pragma once
#include <array>
#include <cmath>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/joints/axis.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace detail {
template <class T, class Axis, int Dir>
struct cylindrical_motion : motion_base<T> {
  static constexpr int nv = 2;
  using rotation_t = std::conditional_t<Axis::fixed, coordinate_rotation<T, (Axis::fixed ? Axis::index : 0)>, Mat3<T>>;
  using axis_t = decltype(axis::signed_unit<T, Axis, Dir>(Vec3d{}));
  rotation_t E;
  axis_t n;  ///< σ·n
  axis_t p;  ///< σ·s·n
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return v[1] * n;
  }
  template <class V>
  FLANGE_INLINE auto pd(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return v[0] * n;
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 2> project(const N& torque, const F& force) const {
    // E·n = n: the force along the axis is the same in both frames.
    return {value_of<T>(dot(n, force)), value_of<T>(dot(n, torque))};
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    if constexpr (K == 0) return motion_pair<zero_vec<T>, axis_t>{{}, n};
    else return motion_pair<axis_t, zero_vec<T>>{n, {}};
  }
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any>
class Cylindrical {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Cylindrical";
  static constexpr role kind = role::joint;
  using axis_type = Axis;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 3> internals{
      {{"s", expr::var_kind::scalar}, {"φ", expr::var_kind::scalar}, {"R_rel", expr::var_kind::rot}}};

  // ---------------------------------------------------------- motion
  static constexpr int nq = 2, nv = 2;
  static constexpr bool reversible = true;
  /// Along n, then about it (core/joint.hpp); the two commute, so connected
  /// either way round.
  static constexpr bool sequential_rates = true;
  static constexpr bool commuting_rates = true;
  /// It turns about its axis but also slides along it: never planar.
  static constexpr int planar_normal() { return Axis::fixed ? Axis::index : -1; }
  static constexpr bool moves_in_plane(int) { return false; }
  /// Closing a loop, it leaves the rotation about n and the translation along it free.
  static constexpr cut_freedom as_cut{.rotations = 1, .translations = 1};

  struct params {
    Vec3d n = Vec3d::UnitZ();  ///< ignored for a compile-time axis
  };
  Cylindrical() : Cylindrical(params{}) {}
  explicit Cylindrical(params p) {
    if constexpr (Axis::fixed) n_ = Axis::unit();
    else n_ = detail::unit_axis(name.view(), type_name, p.n);
  }
  [[nodiscard]] const Vec3d& n() const { return n_; }

  [[nodiscard]] static std::array<double, 2> neutral() { return {0.0, 0.0}; }

  template <class T, int Dir, bool NeedRotation>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    if constexpr (NeedRotation || !Axis::fixed) return motion<T, Dir>(q, cos_sin_of(q[1]));
    else return motion<T, Dir>(q, cos_sin<T>{T(1), T(0)});  // never applied (dynamics/links.hpp: need_rotation)
  }
  /// It turns by one angle, φ = q[1] (core/joint.hpp): its motion with cos φ
  /// and sin φ given.
  static constexpr int angle_coordinate = 1;
  template <class T, int Dir>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q, const cos_sin<T>& a) const {
    detail::cylindrical_motion<T, Axis, Dir> m;
    m.n = axis::signed_unit<T, Axis, Dir>(n_);
    m.p = q[0] * m.n;
    if constexpr (Axis::fixed) {
      m.E.c = a.c;
      m.E.s = Dir > 0 ? a.s : -a.s;
    } else {
      m.E = axis_rotation<T>(m.n.dense(), a);
    }
    return m;
  }
  template <class T>
  void qdot(const T*, const T* v, T* qd) const {
    qd[0] = v[0];
    qd[1] = v[1];
  }
  /// As a cut joint: (s, φ) and their rates from frame_b's pose in frame_a
  /// (R rotates frame_a coordinates into frame_b's, p is frame_b's origin
  /// in frame_a coordinates) and the relative motion w, ṗ (frame_a
  /// coordinates), the inverse of relative_pose on a closed loop.
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>& p, const Vec3<T>& w, const Vec3<T>& pd, T* q, T* v) const {
    Vec3d e1, e2;
    complete_basis(n_, e1, e2);
    q[0] = n_.cast<T>().dot(p);
    q[1] = turn_about<T>(n_, e1, R * e1.cast<T>());
    v[0] = n_.cast<T>().dot(pd);
    v[1] = n_.cast<T>().dot(w);
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> R = axis_rotation<T>(n_.cast<T>(), q[1]);
    set(0, q[0], v[0]);
    set(1, q[1], v[1]);
    set(2, R, Mat3<T>(-tilde<T>(Vec3<T>(n_.cast<T>() * v[1])) * R));
  }
  static constexpr auto s = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto phi = internal_<2, 1, expr::var_kind::scalar>;
  static constexpr auto R_rel = internal_<2, 2, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> n{n_, "n"};
    return boost::hana::make_tuple(
        orientation_eq(R_rel, n * transpose(n) + (identity{} - n * transpose(n)) * cos(phi) - tilde(n) * sin(phi)),
        eq(r_<1>, r_<0> + s * transpose(R_<0>) * n),             //
        orientation_eq(R_<1>, R_rel * R_<0>),                    //
        eq(F_<1>, -(R_rel * F_<0>)),                             //
        eq(M_<1>, -(R_rel * (M_<0> - s * cross(n, F_<0>)))),     //
        eq(zero<shape::scalar>{}, dot(F_<1>, n)),                //
        eq(zero<shape::scalar>{}, dot(M_<1>, n)));
  }

 private:
  Vec3d n_;
};

}  // namespace flange
