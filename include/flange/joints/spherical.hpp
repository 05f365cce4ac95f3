// Spherical: a ball joint, rotation about any axis through one point
// (Modelica's Spherical).
//
//   r₂ = r₁                  F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₁ = 0
//                            M₂ = 0
//
// Frames 1, 2 are frame_a, frame_b; R_rel (the paper's convention: it
// rotates frame_a coordinates into frame_b's) is the internal variable. The
// joint transmits no torque.
//
// Motion (core/joint.hpp): nq = 4, nv = 3. q is the unit quaternion
// (x, y, z, w) of R_rel (math/quaternion.hpp), v = ω, frame_b's angular
// velocity relative to frame_a in frame_b coordinates. E = R_rel(q), p = 0,
// S = (1, 0) in child coordinates, no bias; q̇ = ½·q ⊗ (ω, 0). R_rel is
// computed homogeneously from q, so it is orthogonal to round-off whatever
// |q|; normalising (quaternion_at) sets |q| = 1 again (docs/joints.md). Connected frame_b
// toward the World, the child is frame_a: E = R_relᵀ, S = (−R_relᵀ, 0).
#pragma once
#include <array>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/math/quaternion.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace detail {
/// A spherical joint's motion (core/joint.hpp). No bias: ω is in child
/// coordinates, and reversed, d/dt(−R_relᵀ·ω) = −R_relᵀ·ω̇ − R_relᵀ·(ω × ω).
template <class T, int Dir>
struct spherical_motion : motion_base<T> {
  static constexpr int nv = 3;
  Mat3<T> R;  ///< R_rel(q)
  Mat3<T> E;  ///< R_rel, or R_relᵀ when reversed
  zero_vec<T> p{};
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else if constexpr (Dir > 0) return to_svec(Vec3<T>(v[0], v[1], v[2]));
    else return to_svec(Vec3<T>(-(R.transpose() * Vec3<T>(v[0], v[1], v[2]))));
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 3> project(const N& torque, const F&) const {
    Vec3<T> n = torque.dense();
    if constexpr (Dir < 0) n = -(R * n);
    return {n(0), n(1), n(2)};
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    if constexpr (Dir > 0) return motion_pair<axial_vec<T, K>, zero_vec<T>>{axial<T, K>(T(1)), {}};
    else return motion_pair<dense_vec<T>, zero_vec<T>>{to_svec(Vec3<T>(-R.row(K).transpose())), {}};
  }
};
}  // namespace detail

template <fixed_string Name>
class Spherical {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Spherical";
  static constexpr role kind = role::joint;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 1> internals{{{"R_rel", expr::var_kind::rot}}};

  // ---------------------------------------------------------- motion
  static constexpr int nq = 4, nv = 3;
  /// Its unit quaternion (x, y, z, w) starts at q[0] (core/joint.hpp: quaternion_joint).
  static constexpr int quaternion_at = 0;
  /// ω in the link, after quaternion_at translations along frame_a's axes (core/joint.hpp).
  static constexpr bool ball_rates = true;
  static constexpr bool reversible = true;
  static constexpr int planar_normal() { return -1; }
  static constexpr bool moves_in_plane(int) { return false; }
  /// Closing a loop, it leaves every rotation free and locks the origins together.
  static constexpr cut_freedom as_cut{.rotations = 3, .translations = 0};

  struct params {};
  Spherical() = default;
  explicit Spherical(params) {}

  [[nodiscard]] static std::array<double, 4> neutral() { return {0.0, 0.0, 0.0, 1.0}; }

  template <class T, int Dir, bool>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    detail::spherical_motion<T, Dir> m;
    m.R = quaternion::to_rotation(q);
    if constexpr (Dir > 0) m.E = m.R;
    else m.E = m.R.transpose();
    return m;
  }
  template <class T>
  void qdot(const T* q, const T* v, T* qd) const {
    quaternion::rate(q, v, qd);
  }
  /// As a cut joint: the quaternion of frame_b's orientation in frame_a
  /// and the relative angular velocity in frame_b coordinates.
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>&, const Vec3<T>& w, const Vec3<T>&, T* q, T* v) const {
    quaternion::from_rotation(R, q);
    const Vec3<T> wb = R * w;
    for (int i = 0; i < 3; ++i) v[i] = wb(i);
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> R = quaternion::to_rotation(q);
    set(0, R, Mat3<T>(-tilde<T>(Vec3<T>(v[0], v[1], v[2])) * R));
  }
  template <class T, class Get>
  void read_state(Get&& get, T* q, T* v) const {
    const Mat3<T> R = Eigen::Map<const Mat3<T>>(get(0, false));
    const Mat3<T> Rd = Eigen::Map<const Mat3<T>>(get(0, true));
    quaternion::from_rotation(R, q);
    const Vec3<T> w = vex<T>(R * Rd.transpose());
    for (int i = 0; i < 3; ++i) v[i] = w(i);
  }
  /// A state set by hand: the orientation of frame_b relative to frame_a
  /// and its angular velocity (frame_b coordinates).
  struct state {
    orientation R = {};
    Vec3d w = Vec3d::Zero();
  };
  void write_state(const state& s, double* q, double* v) const {
    detail::require_rotation(name.view(), type_name, "the initial orientation R", s.R.R);
    detail::require_finite(name.view(), type_name, "the initial angular velocity w", s.w);
    quaternion::from_rotation(s.R.R, q);
    for (int i = 0; i < 3; ++i) v[i] = s.w(i);
  }
  [[nodiscard]] state state_from(const double* q, const double* v) const {
    return {{quaternion::to_rotation(q)}, Vec3d(v[0], v[1], v[2])};
  }

  static constexpr auto R_rel = internal_<2, 0, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    return boost::hana::make_tuple(eq(r_<1>, r_<0>),                      //
                                   orientation_eq(R_<1>, R_rel * R_<0>),  //
                                   eq(F_<1>, -(R_rel * F_<0>)),           //
                                   eq(M_<0>, zero<shape::vec>{}),         //
                                   eq(M_<1>, zero<shape::vec>{}));
  }
};

}  // namespace flange
