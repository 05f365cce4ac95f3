// Universal: a Cardan joint, two revolute joints in series — about n_a
// (fixed in frame_a) by φ₁, then about n_b (fixed in frame_b) by φ₂
// (Modelica's Universal).
//
//   R_rel = R(n_b, φ₂)·R(n_a, φ₁),   R(n, φ) = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//   r₂ = r₁                  F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₂ = −R_rel·M₁
//                            0  = M₁·n_a
//                            0  = M₂·n_b
//
// Frames 1, 2 are frame_a, frame_b; φ₁, φ₂ and R_rel are internal variables.
// The axes must not be parallel (they are usually orthogonal).
//
// Motion (core/joint.hpp): nq = nv = 2, q = (φ₁, φ₂). E = R_rel, p = 0, and in
// child coordinates ω = u·φ̇₁ + n_b·φ̇₂ with u = R(n_b, φ₂)·n_a, so S_ω = (u, n_b)
// depends on φ₂ and the bias is Ṡ_ω·v = φ̇₁·φ̇₂·(u × n_b). Connected frame_b
// toward the World it is the universal joint with axes (n_b, n_a) and
// coordinates (−φ₂, −φ₁).
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
/// Rotation about a typed axis by φ: a coordinate rotation or a matrix.
template <class T, class Axis, class N>
FLANGE_INLINE auto typed_axis_rotation(const N& n, const cos_sin<T>& a) {
  if constexpr (Axis::fixed) return coordinate_rotation<T, Axis::index>{a.c, a.s};
  else return Mat3<T>(axis_rotation<T>(n.dense(), a));
}
template <class T, class Axis, class N>
FLANGE_INLINE auto typed_axis_rotation(const N& n, const T& phi) {
  return typed_axis_rotation<T, Axis>(n, cos_sin_of(phi));
}

/// Two revolute axes in series: first about a (fixed in the parent side),
/// then about b (fixed in the child side), by angles (α, β) with rates
/// (α̇, β̇). Dir says which of the joint's coordinates these are: Dir > 0,
/// (α, β) = (φ₁, φ₂); Dir < 0, (α, β) = (−φ₂, −φ₁).
template <class T, class AxisA, class AxisB, int Dir>
struct universal_motion : motion_base<T> {
  static constexpr int nv = 2;
  using first_axis = std::conditional_t<(Dir > 0), AxisA, AxisB>;
  using second_axis = std::conditional_t<(Dir > 0), AxisB, AxisA>;
  using a_t = decltype(axis::signed_unit<T, first_axis, 1>(Vec3d{}));
  using b_t = decltype(axis::signed_unit<T, second_axis, 1>(Vec3d{}));
  using E_t = decltype(compose(typed_axis_rotation<T, second_axis>(b_t{}, T(0)),
                               typed_axis_rotation<T, first_axis>(a_t{}, T(0))));
  using u_t = decltype(rot(typed_axis_rotation<T, second_axis>(b_t{}, T(0)), a_t{}));
  E_t E;
  b_t b;
  u_t u;  ///< the first axis in child coordinates
  zero_vec<T> p{};
  /// (α̇, β̇) from the joint's rates.
  template <class V>
  FLANGE_INLINE std::array<T, 2> rates(const V& v) const {
    if constexpr (Dir > 0) return {v[0], v[1]};
    else return {-v[1], -v[0]};
  }
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) {
      return zero_vec<T>{};
    } else {
      const auto r = rates(v);
      return r[0] * u + r[1] * b;
    }
  }
  template <class V>
  FLANGE_INLINE auto w_bias(const V& v) const {
    const auto r = rates(v);
    return (r[0] * r[1]) * cross(u, b);
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 2> project(const N& torque, const F&) const {
    const T ta = value_of<T>(dot(u, torque)), tb = value_of<T>(dot(b, torque));
    if constexpr (Dir > 0) return {ta, tb};
    else return {-tb, -ta};
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    if constexpr (Dir > 0) {
      if constexpr (K == 0) return motion_pair<u_t, zero_vec<T>>{u, {}};
      else return motion_pair<b_t, zero_vec<T>>{b, {}};
    } else {
      if constexpr (K == 0) return motion_pair<b_t, zero_vec<T>>{-b, {}};
      else return motion_pair<u_t, zero_vec<T>>{-u, {}};
    }
  }
};
}  // namespace detail

template <fixed_string Name, class AxisA = axis::any, class AxisB = axis::any>
class Universal {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Universal";
  static constexpr role kind = role::joint;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 3> internals{
      {{"φ1", expr::var_kind::scalar}, {"φ2", expr::var_kind::scalar}, {"R_rel", expr::var_kind::rot}}};
  static_assert(!(AxisA::fixed && AxisB::fixed && AxisA::index == AxisB::index),
                "flange: a Universal joint's two axes must not be parallel");

  // ---------------------------------------------------------- motion
  static constexpr int nq = 2, nv = 2;
  static constexpr std::array<bool, 2> angles{true, true};  ///< φ₁ and φ₂ (core/joint.hpp)
  static constexpr bool reversible = true;
  /// About n_a, then about n_b (core/joint.hpp).
  static constexpr bool sequential_rates = true;
  static constexpr int planar_normal() { return -1; }
  static constexpr bool moves_in_plane(int) { return false; }
  /// Closing a loop, it leaves the turns about n_a (in frame_a) and n_b (in
  /// frame_b) free: the angle between the two axes is what it keeps.
  static constexpr cut_freedom as_cut{.rotations = 2, .translations = 0};

  struct params {
    Vec3d n_a = Vec3d::UnitX();  ///< the first axis, frame_a coordinates (ignored for a compile-time axis)
    Vec3d n_b = Vec3d::UnitY();  ///< the second axis, frame_b coordinates (ignored for a compile-time axis)
  };
  Universal() : Universal(params{}) {}
  explicit Universal(params p) {
    if constexpr (AxisA::fixed) na_ = AxisA::unit();
    else na_ = detail::unit_axis(name.view(), type_name, p.n_a);
    if constexpr (AxisB::fixed) nb_ = AxisB::unit();
    else nb_ = detail::unit_axis(name.view(), type_name, p.n_b);
    const double sine = na_.cross(nb_).norm();
    if (!(sine > 1e-6))
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": axes n_a = [", na_.transpose(),
                                           "] and n_b = [", nb_.transpose(), "] are parallel (sine of the angle ",
                                           sine, "); a universal joint needs two different axes"));
  }
  [[nodiscard]] const Vec3d& n_a() const { return na_; }
  [[nodiscard]] const Vec3d& n_b() const { return nb_; }

  [[nodiscard]] static std::array<double, 2> neutral() { return {0.0, 0.0}; }

  template <class T, int Dir, bool>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    using M = detail::universal_motion<T, AxisA, AxisB, Dir>;
    using first = typename M::first_axis;
    using second = typename M::second_axis;
    M m;
    const auto a = axis::signed_unit<T, first, 1>(Dir > 0 ? na_ : nb_);
    m.b = axis::signed_unit<T, second, 1>(Dir > 0 ? nb_ : na_);
    const T alpha = Dir > 0 ? q[0] : -q[1], beta = Dir > 0 ? q[1] : -q[0];
    const auto Ra = detail::typed_axis_rotation<T, first>(a, alpha);
    const auto Rb = detail::typed_axis_rotation<T, second>(m.b, beta);
    m.E = compose(Rb, Ra);
    m.u = rot(Rb, a);
    return m;
  }
  template <class T>
  void qdot(const T*, const T* v, T* qd) const {
    qd[0] = v[0];
    qd[1] = v[1];
  }
  /// As a cut joint: (φ₁, φ₂) and their rates from frame_b's orientation R
  /// in frame_a (R rotates frame_a coordinates into frame_b's) and the
  /// relative angular velocity w (frame_a coordinates). R·n_a = R(n_b, φ₂)·n_a
  /// gives φ₂ and Rᵀ·n_b = R(n_a, −φ₁)·n_b gives φ₁; w = n_a·φ̇₁ + Rᵀ·n_b·φ̇₂.
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>&, const Vec3<T>& w, const Vec3<T>&, T* q, T* v) const {
    const Vec3d a_off_b = (na_ - nb_ * nb_.dot(na_)).normalized();  // n_a's part normal to n_b
    const Vec3d b_off_a = (nb_ - na_ * na_.dot(nb_)).normalized();
    const Vec3<T> Ra = R * na_.cast<T>(), Rtb = R.transpose() * nb_.cast<T>();
    q[1] = turn_about<T>(nb_, a_off_b, Ra);
    q[0] = -turn_about<T>(na_, b_off_a, Rtb);
    // w × c = (n_a × c)·φ̇₁ and w × n_a = (c × n_a)·φ̇₂, c = Rᵀ·n_b.
    const Vec3<T> na = na_.cast<T>(), ac = na.cross(Rtb);
    const T ac2 = ac.squaredNorm();
    v[0] = w.cross(Rtb).dot(ac) / ac2;
    v[1] = -w.cross(na).dot(ac) / ac2;
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> Rb = axis_rotation<T>(nb_.cast<T>(), q[1]);
    const Mat3<T> R = Rb * axis_rotation<T>(na_.cast<T>(), q[0]);
    const Vec3<T> w = Rb * na_.cast<T>() * v[0] + nb_.cast<T>() * v[1];
    set(0, q[0], v[0]);
    set(1, q[1], v[1]);
    set(2, R, Mat3<T>(-tilde<T>(w) * R));
  }
  static constexpr auto phi1 = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto phi2 = internal_<2, 1, expr::var_kind::scalar>;
  static constexpr auto R_rel = internal_<2, 2, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> na{na_, "n_a"}, nb{nb_, "n_b"};
    return boost::hana::make_tuple(
        orientation_eq(R_rel, (nb * transpose(nb) + (identity{} - nb * transpose(nb)) * cos(phi2) - tilde(nb) * sin(phi2)) *
                                  (na * transpose(na) + (identity{} - na * transpose(na)) * cos(phi1) -
                                   tilde(na) * sin(phi1))),
        eq(r_<1>, r_<0>),                       //
        orientation_eq(R_<1>, R_rel * R_<0>),   //
        eq(F_<1>, -(R_rel * F_<0>)),            //
        eq(M_<1>, -(R_rel * M_<0>)),            //
        eq(zero<shape::scalar>{}, dot(M_<0>, na)),
        eq(zero<shape::scalar>{}, dot(M_<1>, nb)));
  }

 private:
  Vec3d na_, nb_;
};

}  // namespace flange
