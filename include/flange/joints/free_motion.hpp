// FreeMotion: frame_b free in space relative to frame_a (Modelica's
// FreeMotion): a body flying freely, or a robot's floating base.
//
//   r₂ = r₁ + R₁'·r_rel      F₁ = 0     M₁ = 0
//   R₂ = R_rel·R₁            F₂ = 0     M₂ = 0
//
// Frames 1, 2 are frame_a, frame_b; r_rel (frame_b's origin in frame_a
// coordinates) and R_rel are the internal variables. The joint transmits
// nothing.
//
// Motion (core/joint.hpp): nq = 7, nv = 6. q = (r_rel, Q): the position in
// frame_a coordinates, then the unit quaternion (x, y, z, w) of R_rel
// (math/quaternion.hpp). v = (ṙ_rel, ω): the velocity in frame_a coordinates
// (on the World: the world velocity) and frame_b's angular velocity in frame_b
// coordinates, as Modelica's v_rel_a and w_rel_b. E = R_rel(Q), p = r_rel,
// S_v = 1 (frame_a), S_ω = 1 (frame_b), no bias. It is the same motion as
// three Prismatic joints along frame_a's axes followed by a Spherical joint.
// It must be connected frame_a toward the World.
#pragma once
#include <array>
#include <optional>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/inline.hpp"
#include "flange/math/quaternion.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace detail {
/// A free motion's motion (core/joint.hpp).
template <class T>
struct free_motion_motion : motion_base<T> {
  static constexpr int nv = 6;
  Mat3<T> E;
  dense_vec<T> p;
  template <class V>
  FLANGE_INLINE auto w(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return to_svec(Vec3<T>(v[3], v[4], v[5]));
  }
  template <class V>
  FLANGE_INLINE auto pd(const V& v) const {
    if constexpr (is_no_rates<V>) return zero_vec<T>{};
    else return to_svec(Vec3<T>(v[0], v[1], v[2]));
  }
  template <class N, class F>
  FLANGE_INLINE std::array<T, 6> project(const N& torque, const F& force) const {
    // rot_t, not Eigen's product: inlined however large the caller's unit is
    const Vec3<T> f = rot_t(E, force).dense(), n = torque.dense();
    return {f(0), f(1), f(2), n(0), n(1), n(2)};
  }
  template <int K>
  FLANGE_INLINE auto col() const {
    if constexpr (K < 3) return motion_pair<zero_vec<T>, dense_vec<T>>{{}, to_svec(Vec3<T>(E.col(K)))};
    else return motion_pair<axial_vec<T, (K - 3)>, zero_vec<T>>{axial<T, (K - 3)>(T(1)), {}};
  }
  /// T·r and Tᵀ·a for T = diag(E, 1) (core/joint.hpp, turned_subspace): the
  /// columns are those at E = 1 with the linear rates turned by E. Written
  /// into out entry by entry, as the next step reads them.
  FLANGE_INLINE void turn_rates(const T* r, T* out) const {
    const auto l = rot(E, to_svec(Vec3<T>(r[0], r[1], r[2])));
    for (int i = 0; i < 3; ++i) out[i] = l.dense()[i];
    for (int i = 3; i < 6; ++i) out[i] = r[i];
  }
  FLANGE_INLINE void unturn_rates(const T* a, T* out) const {
    const auto l = rot_t(E, to_svec(Vec3<T>(a[0], a[1], a[2])));
    for (int i = 0; i < 3; ++i) out[i] = l.dense()[i];
    for (int i = 3; i < 6; ++i) out[i] = a[i];
  }
};
}  // namespace detail

template <fixed_string Name>
class FreeMotion {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "FreeMotion";
  static constexpr role kind = role::joint;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"r_rel", expr::var_kind::vec}, {"R_rel", expr::var_kind::rot}}};

  // ---------------------------------------------------------- motion
  static constexpr int nq = 7, nv = 6;
  /// Its unit quaternion (x, y, z, w) starts at q[3] (core/joint.hpp: quaternion_joint).
  static constexpr int quaternion_at = 3;
  /// ω in the link, after quaternion_at translations along frame_a's axes (core/joint.hpp).
  static constexpr bool ball_rates = true;
  static constexpr bool reversible = false;
  /// Its columns are constant but for its linear rates, in frame_a's
  /// coordinates: S(q) = S₀·diag(E, 1) (core/joint.hpp).
  static constexpr bool turned_subspace = true;
  static constexpr int planar_normal() { return -1; }
  static constexpr bool moves_in_plane(int) { return false; }
  /// Closing a loop, it leaves everything free: the loop has no constraint.
  static constexpr cut_freedom as_cut{.rotations = 3, .translations = 3};

  struct params {};
  FreeMotion() = default;
  explicit FreeMotion(params) {}

  [[nodiscard]] static std::array<double, 7> neutral() { return {0, 0, 0, 0, 0, 0, 1}; }

  template <class T, int Dir, bool>
  [[nodiscard]] FLANGE_INLINE auto motion(const T* q) const {
    // Dir < 0 never reaches here: the scene refuses a FreeMotion connected
    // frame_b toward the World (reversible = false) with its own diagnostic.
    detail::free_motion_motion<T> m;
    m.E = quaternion::to_rotation(q + 3);
    m.p = to_svec(Vec3<T>(q[0], q[1], q[2]));
    return m;
  }
  template <class T>
  void qdot(const T* q, const T* v, T* qd) const {
    for (int i = 0; i < 3; ++i) qd[i] = v[i];
    quaternion::rate(q + 3, v + 3, qd + 3);
  }
  /// As a cut joint: (r_rel, Q) and (ṙ_rel, ω) from frame_b's pose in
  /// frame_a (R rotates frame_a coordinates into frame_b's, p is frame_b's
  /// origin in frame_a coordinates) and the relative motion w, ṗ (frame_a
  /// coordinates; ω is in frame_b's).
  template <class T>
  void cut_state(const Mat3<T>& R, const Vec3<T>& p, const Vec3<T>& w, const Vec3<T>& pd, T* q, T* v) const {
    quaternion::from_rotation(R, q + 3);
    const Vec3<T> wb = R * w;
    for (int i = 0; i < 3; ++i) {
      q[i] = p(i);
      v[i] = pd(i);
      v[3 + i] = wb(i);
    }
  }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const {
    const Mat3<T> R = quaternion::to_rotation(q + 3);
    set(0, Vec3<T>(q[0], q[1], q[2]), Vec3<T>(v[0], v[1], v[2]));
    set(1, R, Mat3<T>(-tilde<T>(Vec3<T>(v[3], v[4], v[5])) * R));
  }
  template <class T, class Get>
  void read_state(Get&& get, T* q, T* v) const {
    for (int i = 0; i < 3; ++i) {
      q[i] = get(0, false)[i];
      v[i] = get(0, true)[i];
    }
    const Mat3<T> R = Eigen::Map<const Mat3<T>>(get(1, false));
    const Mat3<T> Rd = Eigen::Map<const Mat3<T>>(get(1, true));
    quaternion::from_rotation(R, q + 3);
    const Vec3<T> w = vex<T>(R * Rd.transpose());
    for (int i = 0; i < 3; ++i) v[3 + i] = w(i);
  }
  /// A state set by hand: frame_b's position and velocity in frame_a
  /// coordinates, its orientation, and its angular velocity (frame_b
  /// coordinates). Or, instead of v, v_cm: the velocity (frame_a coordinates,
  /// relative to frame_a) of the centre of mass of everything frame_b
  /// carries; set_joint and initial_state then work out v from the scene's
  /// bodies, with w and every other joint's rates as given:
  ///
  ///   set_joint<"base">(robot, x, {.R = orientation::rpy(0, 0.1, 0), .w = {0, 0, 2}, .v_cm = Vec3d(1, 0, 0)});
  struct state {
    Vec3d r = Vec3d::Zero();
    Vec3d v = Vec3d::Zero();
    orientation R = {};
    Vec3d w = Vec3d::Zero();
    std::optional<Vec3d> v_cm = std::nullopt;
  };
  void write_state(const state& s, double* q, double* v) const {
    detail::require_finite(name.view(), type_name, "the initial position r", s.r);
    detail::require_finite(name.view(), type_name, "the initial velocity v", s.v);
    if (s.v_cm) {
      detail::require_finite(name.view(), type_name, "the initial centre-of-mass velocity v_cm", *s.v_cm);
      if (s.v != Vec3d::Zero())
        throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": both v = [", s.v.transpose(),
                                             "] and v_cm are given; give the velocity of frame_b (v) or of the ",
                                             "centre of mass (v_cm), not both"));
    }
    detail::require_rotation(name.view(), type_name, "the initial orientation R", s.R.R);
    detail::require_finite(name.view(), type_name, "the initial angular velocity w", s.w);
    for (int i = 0; i < 3; ++i) q[i] = s.r(i), v[i] = s.v(i), v[3 + i] = s.w(i);
    quaternion::from_rotation(s.R.R, q + 3);
  }
  [[nodiscard]] state state_from(const double* q, const double* v) const {
    return {Vec3d(q[0], q[1], q[2]), Vec3d(v[0], v[1], v[2]), {quaternion::to_rotation(q + 3)}, Vec3d(v[3], v[4], v[5])};
  }

  static constexpr auto r_rel = internal_<2, 0, expr::var_kind::vec>;
  static constexpr auto R_rel = internal_<2, 1, expr::var_kind::rot>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    return boost::hana::make_tuple(eq(r_<1>, r_<0> + transpose(R_<0>) * r_rel),  //
                                   orientation_eq(R_<1>, R_rel * R_<0>),          //
                                   eq(F_<0>, zero<shape::vec>{}),                 //
                                   eq(M_<0>, zero<shape::vec>{}),                 //
                                   eq(F_<1>, zero<shape::vec>{}),                 //
                                   eq(M_<1>, zero<shape::vec>{}));
  }
};

}  // namespace flange
