// Planar: frame_b moves in a plane of frame_a — two translations s_x, s_y
// along e_x, e_y and a rotation φ about the plane's normal n (Modelica's
// Planar). e_x is n_x made orthogonal to n, e_y = n × e_x, all in frame_a
// coordinates, as Modelica does.
//
//   R_rel = n·n' + (1 − n·n')·cos φ − ñ·sin φ
//   r₂ = r₁ + R₁'·(s_x·e_x + s_y·e_y)     F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁                          M₂ = −R_rel·(M₁ − (s_x·e_x + s_y·e_y) × F₁)
//                                          0 = F₁·e_x,  0 = F₁·e_y,  0 = M₂·n
//
// Frames 1, 2 are frame_a, frame_b; s_x, s_y, φ and R_rel are internal
// variables.
//
// Motion (core/joint.hpp): nq = nv = 3, q = (s_x, s_y, φ). E = R_rel, p =
// s_x·e_x + s_y·e_y, ṗ = ṡ_x·e_x + ṡ_y·e_y (frame_a coordinates, so no bias),
// ω = n·φ̇. Planar<"p", axis::z, axis::x> fixes the plane at compile time: a
// scene of such joints and Revolutes about z runs planar arithmetic. It must
// be connected frame_a toward the World.
#pragma once
#include <array>
#include <cmath>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/joints/axis.hpp"
#include "flange/joints/universal.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace detail {
/// e_y = n × e_x as a typed vector: along a coordinate axis, with its sign,
/// when n and e_x are coordinate axes.
template <class T, class Normal, class First>
auto planar_second_axis(const Vec3d& ey) {
  if constexpr (Normal::fixed && First::fixed) {
    constexpr int i = Normal::index, j = First::index, k = 3 - i - j;
    (void)ey;
    return axial<T, k>(T(j == (i + 1) % 3 ? 1 : -1));
  } else {
    return to_svec(Vec3<T>(ey.cast<T>()));
  }
}

template <class T, class Normal, class First>
struct planar_motion : motion_base<T> {
  static constexpr int nv = 3;
  using n_t = decltype(axis::signed_unit<T, Normal, 1>(Vec3d{}));
  using ex_t = decltype(axis::signed_unit<T, std::conditional_t<(Normal::fixed && First::fixed), First, axis::any>, 1>(
      Vec3d{}));
  using ey_t = decltype(planar_second_axis<T, Normal, First>(Vec3d{}));
  using E_t = decltype(typed_axis_rotation<T, Normal>(n_t{}, T(0)));
  E_t E;
  n_t n;
  ex_t ex;
  ey_t ey;
  decltype(std::declval<T>() * ex_t{} + std::declval<T>() * ey_t{}) p;
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return v[2] * n;
  }
  template <class V>
  FLANGE_INLINE auto pd(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return v[0] * ex + v[1] * ey;
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 3> project(const N& torque, const F& force) const {
    const auto fa = rot_t(E, force);
    return {value_of<T>(dot(ex, fa)), value_of<T>(dot(ey, fa)), value_of<T>(dot(n, torque))};
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    if constexpr (K == 0) return motion_pair{zero_vec<T>{}, rot(E, ex)};
    else if constexpr (K == 1) return motion_pair{zero_vec<T>{}, rot(E, ey)};
    else return motion_pair{n, zero_vec<T>{}};
  }
};
}  // namespace detail

template <fixed_string Name, class Normal = axis::any, class First = axis::any>
class Planar {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Planar";
  static constexpr role kind = role::joint;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 4> internals{{{"s_x", expr::var_kind::scalar},
                                                           {"s_y", expr::var_kind::scalar},
                                                           {"φ", expr::var_kind::scalar},
                                                           {"R_rel", expr::var_kind::rot}}};
  static_assert(!(Normal::fixed && First::fixed && Normal::index == First::index),
                "flange: a Planar joint's first axis n_x must not be its normal n");

  // ---------------------------------------------------------- motion
  static constexpr int nq = 3, nv = 3;
  static constexpr bool reversible = false;
  /// Along e_x, along e_y, then about n (core/joint.hpp).
  static constexpr bool sequential_rates = true;
  static constexpr int planar_normal() { return Normal::fixed ? Normal::index : -1; }
  static constexpr bool moves_in_plane(int k) { return Normal::fixed && First::fixed && Normal::index == k; }
  /// Closing a loop, it leaves the rotation about n and the translations
  /// normal to it free.
  static constexpr cut_freedom as_cut{.rotations = 1, .translations = 2};

  struct params {
    Vec3d n = Vec3d::UnitZ();    ///< the plane's normal, frame_a coordinates (ignored for a compile-time axis)
    Vec3d n_x = Vec3d::UnitX();  ///< the first translation direction (ignored for a compile-time axis)
  };
  Planar() : Planar(params{}) {}
  explicit Planar(params p) {
    if constexpr (Normal::fixed) n_ = Normal::unit();
    else n_ = detail::unit_axis(name.view(), type_name, p.n);
    Vec3d nx;
    if constexpr (First::fixed) nx = First::unit();
    else nx = detail::unit_axis(name.view(), type_name, p.n_x);
    const Vec3d ey = n_.cross(nx);
    if (!(ey.norm() > 1e-6))
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": n_x = [", nx.transpose(),
                                           "] is parallel to the normal n = [", n_.transpose(),
                                           "]; give a direction in the plane"));
    ey_ = ey.normalized();
    ex_ = ey_.cross(n_);
  }
  [[nodiscard]] const Vec3d& n() const { return n_; }
  [[nodiscard]] const Vec3d& e_x() const { return ex_; }
  [[nodiscard]] const Vec3d& e_y() const { return ey_; }

  [[nodiscard]] static std::array<double, 3> neutral() { return {0.0, 0.0, 0.0}; }

  template <class T, int Dir, bool>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    return motion<T, Dir>(q, cos_sin_of(q[2]));
  }
  /// It turns by one angle, φ = q[2] (core/joint.hpp): its motion with cos φ
  /// and sin φ given.
  static constexpr int angle_coordinate = 2;
  template <class T, int>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q, const cos_sin<T>& a) const {
    using M = detail::planar_motion<T, Normal, First>;
    M m;
    m.n = axis::signed_unit<T, Normal, 1>(n_);
    m.ex = axis::signed_unit<T, std::conditional_t<(Normal::fixed && First::fixed), First, axis::any>, 1>(ex_);
    m.ey = detail::planar_second_axis<T, Normal, First>(ey_);
    m.E = detail::typed_axis_rotation<T, Normal>(m.n, a);
    m.p = q[0] * m.ex + q[1] * m.ey;
    return m;
  }
  template <class T>
  void qdot(const T*, const T* v, T* qd) const {
    for (int i = 0; i < 3; ++i) qd[i] = v[i];
  }
  /// As a cut joint: (s_x, s_y, φ) and their rates from frame_b's pose and
  /// motion in frame_a (as Cylindrical's).
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>& p, const Vec3<T>& w, const Vec3<T>& pd, T* q, T* v) const {
    q[0] = ex_.cast<T>().dot(p);
    q[1] = ey_.cast<T>().dot(p);
    q[2] = turn_about<T>(n_, ex_, R * ex_.cast<T>());
    v[0] = ex_.cast<T>().dot(pd);
    v[1] = ey_.cast<T>().dot(pd);
    v[2] = n_.cast<T>().dot(w);
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> R = axis_rotation<T>(n_.cast<T>(), q[2]);
    for (int i = 0; i < 3; ++i) set(i, q[i], v[i]);
    set(3, R, Mat3<T>(-tilde<T>(Vec3<T>(n_.cast<T>() * v[2])) * R));
  }
  static constexpr auto s_x = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto s_y = internal_<2, 1, expr::var_kind::scalar>;
  static constexpr auto phi = internal_<2, 2, expr::var_kind::scalar>;
  static constexpr auto R_rel = internal_<2, 3, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> n{n_, "n"}, ex{ex_, "e_x"}, ey{ey_, "e_y"};
    return boost::hana::make_tuple(
        orientation_eq(R_rel, n * transpose(n) + (identity{} - n * transpose(n)) * cos(phi) - tilde(n) * sin(phi)),
        eq(r_<1>, r_<0> + transpose(R_<0>) * (s_x * ex + s_y * ey)),             //
        orientation_eq(R_<1>, R_rel * R_<0>),                                     //
        eq(F_<1>, -(R_rel * F_<0>)),                                              //
        eq(M_<1>, -(R_rel * (M_<0> - cross(s_x * ex + s_y * ey, F_<0>)))),        //
        eq(zero<shape::scalar>{}, dot(F_<0>, ex)),                                //
        eq(zero<shape::scalar>{}, dot(F_<0>, ey)),                                //
        eq(zero<shape::scalar>{}, dot(M_<1>, n)));
  }

 private:
  Vec3d n_, ex_, ey_;
};

}  // namespace flange
