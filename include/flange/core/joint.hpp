// What a joint is: the concept every joint type models, and the pieces of
// motion and force arithmetic that joints share.
//
// A joint J is a component (core/component.hpp) with role::joint and two
// frames, frame_a and frame_b, that also declares everything about its own
// motion, the way a Pinocchio joint model does. The algorithms ask it; they
// never switch on a list of joint kinds.
//
//   static constexpr int nq, nv;      sizes of its configuration q and its
//                                     velocity v (they differ for quaternions)
//   static constexpr bool reversible; may it be connected frame_b toward the World
//   neutral()                         its neutral configuration, std::array<double, nq>
//   motion<T, Dir, NeedRotation>(q)   its motion at q (below); Dir = +1 when
//                                     frame_a faces the World, −1 otherwise
//   qdot(q, v, qd)                    q̇ from v
//   write_internals(q, v, set)        its DAE internals (φ, R_rel, …) and their rates
//   read_state(get, q, v)             q and v back from those internals (the
//                                     residual's inputs); a plain joint
//                                     (plain_joint below) may leave it out
//   planar_normal(), moves_in_plane(K)  what planar arithmetic needs to know
//
// and optionally:
//   state, write_state(s, q, v), state_from(q, v)  the state set by hand
//                                (set_joint) and read back (get_joint); a
//                                plain joint's default is {.q, .v}
//   quaternion_at = k            a unit quaternion in q from q[k]: it is kept
//                                at unit norm and checked (normalize_joint,
//                                check_joint_coordinates below); normalize(q)
//                                and check_coordinates(q) for invariants of
//                                another kind (without any, q is always valid)
//   relative_pose(q)             frame_b's pose in frame_a; without it, the
//                                motion<+1>(q) densified (relative_pose_of);
//                                tests/joint_laws_test.cpp holds a joint's
//                                own to its motion
//   generalized_force(t, x, q, v, tau)  inputs and axis laws on its coordinates
//   elastic_energy(q)            the potential energy of its axis law
//   force_reads_state            false when generalized_force reads only the
//                                joint's own q and v and the time (no input
//                                f(t, x)); without it, true: its exact
//                                Jacobian then takes every direction
//   fixed_subspace               true when m.col<k>() is the same at every q,
//                                either way round: a scene whose joints all
//                                hang from the World folds its constant mass
//                                matrix (dynamics/model.hpp)
//   turned_subspace              true when the columns are a constant S₀
//                                turned by an orthogonal T(q) acting on the
//                                rates, S(q) = S₀·T(q), with m.turn_rates(r,
//                                out) writing T·r and m.unturn_rates(a, out)
//                                Tᵀ·a (a FreeMotion, whose linear rates are
//                                in frame_a's coordinates): its block of M is
//                                Tᵀ·M₀·T, and folds as M₀
//   ball_rates                   true when, connected frame_a toward the
//                                World, its last three rates are its link's
//                                angular velocity relative to the parent in
//                                the link's coordinates, its quaternion
//                                (quaternion_at, R homogeneous in it) turns
//                                with q̇ = ½·Q ⊗ (ω, 0), and the rates before
//                                them (quaternion_at of them) are
//                                translations along the parent's axes, q = v
//                                (a Spherical, a FreeMotion): the analytic
//                                Jacobian takes it (dynamics/derivatives.hpp)
//   sequential_rates             true when, connected frame_a toward the
//                                World, it moves as one-rate joints in series
//                                in the order of its rates, q = v: rate k's
//                                column is fixed in the frame that the rates
//                                before it have moved (as a joint's axis in a
//                                massless link between them), so that a change
//                                of q_k moves the joint's frame_b by that
//                                column (a Universal, a Cylindrical, a
//                                Planar): the analytic Jacobian takes it as a
//                                row of one-rate joints (dynamics/derivatives.hpp)
//   commuting_rates              with sequential_rates: true when its columns
//                                commute (each fixed in the frames the others
//                                move: a Cylindrical's turn about n and slide
//                                along it), so that connected frame_b toward
//                                the World, its rates in the other order, it
//                                is still such a row
//   as_cut, cut_state(R, p, w, ṗ, q, v)  what it leaves free when it closes a
//                                loop (cut_freedom below; without it, it
//                                cannot be cut), and its coordinates and rates
//                                from its frames' relative pose and motion
//   angles = {…}                 which coordinates are angles (the same pose
//                                at q_k and q_k + 2π), std::array<bool, nq>;
//                                without it, its angle_coordinate (below) if
//                                it has one (periodic_coordinates)
//
// scene/joint_check.hpp turns a missing member into one static_assert naming
// the joint and the member.
//
// A joint whose rotation turns by one angle φ = q[k] may declare
// angle_coordinate = k and motion<T, Dir>(q, cos_sin<T>{cos φ, sin φ}): its
// motion with the cosine and sine given. dynamics/links.hpp then computes
// every such link's cosine and sine in one call (math/sincos.hpp) instead of
// a call per link.
//
// A joint that turns about one axis n, fixed in both its frames but known
// only at run time, may also declare axis_frame = true, n() and
// motion_in_axis_frame<T, Dir, NeedRotation>(q), with
// motion_in_axis_frame<T, Dir>(q, cos_sin<T>) beside it: its motion in
// coordinates turned so that n is e_z, which has the typed form of a joint
// about z, at its angle φ or at φ + θ₀ (a frame turned about the axis by a
// constant). Its link then computes in those coordinates
// (dynamics/axis_frames.hpp), and the algorithms see a typed motion subspace
// instead of a dense one.
//
// The motion object m at q, for the link behind the joint (the child):
//
//   m.E              rotates frame_a coordinates into child coordinates
//   m.p              the child origin in frame_a coordinates
//   m.w(v)           the relative angular velocity S_ω·v, child coordinates
//   m.pd(v)          the relative velocity of the child origin S_v·v = ṗ,
//                    frame_a coordinates
//   m.w_bias(v)      Ṡ_ω·v, and m.pd_bias(v): Ṡ_v·v (frame_a coordinates):
//                    the acceleration the joint adds at v̇ = 0
//   m.project(n, f)  Sᵀ·(n, f) = S_ωᵀ·n + S_vᵀ·Eᵀ·f for a torque n and force f
//                    on the child at its origin (child coordinates): the
//                    generalized forces, std::array<T, nv>
//   m.col<k>()       column k of the motion subspace: {ang, lin} in child
//                    coordinates (lin = E·S_v·e_k)
//
// A motion object derived from motion_base<T> (below) states only what is
// not zero: pd, w_bias and pd_bias default to zero.
//
// v is a pointer to the joint's nv rates, or no_rates{} when the rates are
// known to be zero (their terms are then never generated). Every quantity has
// a type from math/sparse.hpp, so what a joint's type rules out (a rotation
// about a coordinate axis, no translation) costs nothing in the algorithms.
#pragma once
#include <array>
#include <cmath>
#include <concepts>
#include <string>
#include <type_traits>
#include <utility>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/detail/inline.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/math/quaternion.hpp"
#include "flange/math/sincos.hpp"
#include "flange/math/sparse.hpp"

namespace flange {

/// Rates known to be zero.
struct no_rates {};

template <class V>
inline constexpr bool is_no_rates = std::is_same_v<std::remove_cvref_t<V>, no_rates>;

/// A typed spatial quantity in two parts: motion {angular, linear} or force
/// {torque n, force f}, both in one frame at its origin.
template <class A, class L>
struct motion_pair {
  A ang;
  L lin;
};
template <class N, class F>
struct force_pair {
  N n;
  F f;
};
template <class A, class L>
motion_pair(A, L) -> motion_pair<A, L>;
template <class N, class F>
force_pair(N, F) -> force_pair<N, F>;

/// What a motion object (above) states by default: a joint derives its
/// motion object from motion_base<T> and writes only what is not zero. By
/// default the child origin does not move in frame_a (pd = 0) and the motion
/// subspace does not change with the motion (both biases 0): a Revolute's
/// motion states E, w, project and col only. A member of the joint's own
/// hides the default of the same name.
template <class T>
struct motion_base {
  template <class V>
  FLANGE_INLINE zero_vec<T> pd(const V&) const {
    return {};
  }
  template <class V>
  FLANGE_INLINE zero_vec<T> w_bias(const V&) const {
    return {};
  }
  template <class V>
  FLANGE_INLINE zero_vec<T> pd_bias(const V&) const {
    return {};
  }
};

/// frame_b's pose relative to frame_a: R rotates frame_a coordinates into
/// frame_b's, p is frame_b's origin in frame_a coordinates.
template <class T>
struct pose {
  Mat3<T> R;
  Vec3<T> p;
};

/// The flows of a massless two-frame component (a joint or a rigid edge) at
/// frame_a from those at frame_b, and the reverse: its force and moment
/// balance, F_a + Rᵀ·F_b = 0 and M_a + Rᵀ·M_b + p × Rᵀ·F_b = 0.
template <class T>
wrench<T> flows_a_from_b(const pose<T>& x, const wrench<T>& b) {
  const Vec3<T> Fa = -(x.R.transpose() * b.f);
  return {Fa, x.p.cross(Fa) - x.R.transpose() * b.n};
}
template <class T>
wrench<T> flows_b_from_a(const pose<T>& x, const wrench<T>& a) {
  return {-(x.R * a.f), x.R * (x.p.cross(a.f) - a.n)};
}
FLANGE_COMMON(wrench<double> flows_a_from_b<double>(const pose<double>&, const wrench<double>&))
FLANGE_COMMON(wrench<double> flows_b_from_a<double>(const pose<double>&, const wrench<double>&))

/// What a cut joint (one that closes a kinematic loop, dynamics/loops.hpp)
/// leaves free between its frames; the loop's constraints lock the rest.
///
///   rotations     0; 1, about its axis n() (Revolute, Cylindrical, Planar);
///                 2, about n_a() fixed in frame_a then n_b() fixed in
///                 frame_b (Universal: the angle between the two axes is
///                 kept); 3 (Spherical, FreeMotion)
///   translations  0; 1, along n() (Prismatic, Cylindrical); 2, normal to
///                 n() (Planar); 3 (FreeMotion)
struct cut_freedom {
  int rotations = 0;
  int translations = 0;
};

namespace detail {
/// Whether a joint has a generalized force of its own (an input or an axis law).
template <class J>
concept has_generalized_force = requires(const J& j, const double* p, double* tau, const joint_state<double>& x) {
  j.generalized_force(0.0, x, p, p, tau);
};

/// Whether a joint's generalized force may read other joints' states (an
/// input f(t, x)): the optional member force_reads_state, true where a joint
/// with a force does not say.
template <class J>
constexpr bool force_reads_state() {
  if constexpr (!has_generalized_force<J>) return false;
  else if constexpr (requires { J::force_reads_state; }) return J::force_reads_state;
  else return true;
}

/// A joint type that can close a loop: it says what it leaves free, and
/// has no force of its own (a drive or an axis law on a cut joint would act
/// on a coordinate the state does not have).
template <class J>
concept cuttable = requires {
  { J::as_cut } -> std::convertible_to<cut_freedom>;
} && !has_generalized_force<J>;
}  // namespace detail

/// Whether a joint offers an axis frame (above): a run-time axis n() its
/// link may be turned to, and its motion in that frame.
/// Whether a joint turns by one angle whose cosine and sine may be given
/// (above).
template <class J>
concept angle_joint = requires(const J& j, const double* q, const cos_sin<double>& a) {
  requires J::angle_coordinate >= 0 && J::angle_coordinate < J::nq;
  j.template motion<double, 1>(q, a);
};

/// Which of a joint's coordinates are angles, each giving the same pose at
/// q_k and q_k + 2π: its own `angles` if it declares them, else its
/// angle_coordinate, else none. A cut joint's angles are read from its frames
/// within (−π, π]; get_joint unwraps them along a run with these.
template <class J>
constexpr std::array<bool, J::nq> periodic_coordinates() {
  if constexpr (requires { J::angles; }) {
    return J::angles;
  } else {
    std::array<bool, J::nq> a{};
    if constexpr (angle_joint<J>) a[J::angle_coordinate] = true;
    return a;
  }
}

template <class J>
concept axis_framed_joint = angle_joint<J> && requires(const J& j, const double* q, const cos_sin<double>& a) {
  requires J::axis_frame;
  { j.n() } -> std::convertible_to<Vec3d>;
  j.template motion_in_axis_frame<double, 1, true>(q);
  j.template motion_in_axis_frame<double, 1>(q, a);
};

/// frame_b's pose in frame_a at q: the joint's relative_pose(q) if it
/// declares one, else its motion at q with frame_a toward the World (E
/// rotates frame_a coordinates into frame_b's, p is frame_b's origin in
/// frame_a), densified.
template <class J, class T>
pose<T> relative_pose_of(const J& j, const T* q) {
  if constexpr (requires { j.relative_pose(q); }) {
    return j.relative_pose(q);
  } else {
    const auto m = j.template motion<T, 1, true>(q);
    pose<T> x;
    x.R = dense_rotation<T>(m.E);
    x.p = m.p.dense();
    return x;
  }
}

/// Whether a joint's coordinates hold a unit quaternion (x, y, z, w) from
/// q[J::quaternion_at] on (a Spherical's at 0, a FreeMotion's at 3):
/// normalize_joint and check_joint_coordinates below then know what to do.
template <class J>
concept quaternion_joint = requires {
  { J::quaternion_at } -> std::convertible_to<int>;
  requires J::quaternion_at >= 0 && J::quaternion_at + 4 <= J::nq;
};

/// Keeps q valid: the joint's normalize(q) if it declares one; else its
/// quaternion back to unit norm (quaternion_joint); a joint with neither has
/// no invalid q.
template <class J, class T>
void normalize_joint(const J& j, T* q) {
  if constexpr (requires { j.normalize(q); }) j.normalize(q);
  else if constexpr (quaternion_joint<J>) quaternion::normalize(q + J::quaternion_at);
}

/// Throws parameter_error naming the joint if its coordinates are not valid:
/// the joint's check_coordinates(q) if it declares one; else a quaternion
/// whose squared norm is off 1 by more than 1e-6, an input mistake (written
/// by hand, not from an orientation), not drift.
template <class J, class T>
void check_joint_coordinates(const J& j, const T* q) {
  if constexpr (requires { j.check_coordinates(q); }) {
    j.check_coordinates(q);
  } else if constexpr (quaternion_joint<J>) {
    const T* e = q + J::quaternion_at;
    const double n2 = static_cast<double>(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
    if (!(std::abs(n2 - 1) <= 1e-6))
      throw parameter_error(detail::concat(J::type_name, " \"", J::name.view(), "\": its quaternion (x, y, z, w) = [",
                                           static_cast<double>(e[0]), ", ", static_cast<double>(e[1]), ", ",
                                           static_cast<double>(e[2]), ", ", static_cast<double>(e[3]),
                                           "] has squared norm ", n2,
                                           ", not 1; set it with set_joint from an orientation, or normalize(scene, x)"));
  }
}

/// Whether a joint's normalize(q) changes anything, so that a stepper must
/// project between steps: a joint says so with `static constexpr bool
/// normalizes`; by default, a joint whose coordinates outnumber its rates
/// (a quaternion) does, and one with as many (angles, lengths) does not.
template <class J>
constexpr bool normalizes() {
  if constexpr (requires { J::normalizes; }) return J::normalizes;
  else return J::nq != J::nv;
}

/// Whether a joint is plain: as many coordinates as rates, and its first nq
/// internals (write_internals) are those coordinates, scalars, in order (a
/// Revolute's φ, a Planar's s_x, s_y, φ). A plain joint may leave out
/// read_state, state and write_state: the defaults below read and set its
/// coordinates and rates as they are.
template <class J>
constexpr bool plain_joint() {
  if constexpr (!requires { J::internals; } || J::nq != J::nv || quaternion_joint<J>) {
    return false;
  } else {
    if (static_cast<int>(J::internals.size()) < J::nq) return false;
    for (int i = 0; i < J::nq; ++i)
      if (J::internals[i].kind != expr::var_kind::scalar) return false;
    return true;
  }
}

/// A plain joint's state set by hand: its coordinate and rate {.q, .v}, or
/// for several, {.q = {…}, .v = {…}}.
template <int N>
struct coordinate_state {
  std::array<double, N> q{}, v{};
};
template <>
struct coordinate_state<1> {
  double q = 0, v = 0;
};

namespace detail {
template <class J>
struct joint_state_type {
  using type = coordinate_state<J::nq>;
};
template <class J>
  requires requires { typename J::state; }
struct joint_state_type<J> {
  using type = typename J::state;
};
}  // namespace detail

/// The type a joint's state is set from (set_joint, initial_state): its own
/// state, or a plain joint's coordinate_state.
template <class J>
using joint_state_t = typename detail::joint_state_type<J>::type;

/// Sets q and v from a state set by hand: the joint's own write_state, or a
/// plain joint's coordinates and rates, each checked to be finite.
template <class J>
void write_joint_state(const J& j, const joint_state_t<J>& s, double* q, double* v) {
  if constexpr (requires { j.write_state(s, q, v); }) {
    j.write_state(s, q, v);
  } else {
    static_assert(plain_joint<J>(), "flange: a joint that is not plain (core/joint.hpp: plain_joint) states its own "
                                    "struct state and write_state(s, q, v)");
    const auto at = [](const auto& a, int i) {
      if constexpr (J::nq == 1) return a;
      else return a[static_cast<std::size_t>(i)];
    };
    const auto check = [](const char* what, int i, double x) {
      if (!std::isfinite(x))  // the message is built only for a number that fails
        detail::require_finite(J::name.view(), J::type_name,
                               J::nq == 1 ? std::string(what) : detail::concat(what, " ", i), x);
    };
    for (int i = 0; i < J::nq; ++i) {
      check("the initial coordinate", i, at(s.q, i));
      check("the initial rate", i, at(s.v, i));
      q[i] = at(s.q, i);
      v[i] = at(s.v, i);
    }
  }
}

/// A joint's state in its own terms at (q, v), the inverse of
/// write_joint_state: the joint's state_from(q, v), or a plain joint's
/// coordinates and rates.
template <class J>
joint_state_t<J> read_joint_value(const J& j, const double* q, const double* v) {
  if constexpr (requires { j.state_from(q, v); }) {
    return j.state_from(q, v);
  } else {
    static_assert(plain_joint<J>(), "flange: a joint that is not plain (core/joint.hpp: plain_joint) states its own "
                                    "state_from(q, v), the inverse of its write_state");
    joint_state_t<J> s;
    if constexpr (J::nq == 1) {
      s.q = q[0];
      s.v = v[0];
    } else {
      for (int i = 0; i < J::nq; ++i) s.q[i] = q[i], s.v[i] = v[i];
    }
    return s;
  }
}

/// q and v back from the joint's internals, get(i, rate) pointing at the
/// value or rate of internal i (the residual's inputs): the joint's own
/// read_state, or a plain joint's first nq internals.
template <class J, class T, class Get>
void read_joint_state(const J& j, Get&& get, T* q, T* v) {
  if constexpr (requires { j.read_state(get, q, v); }) {
    j.read_state(get, q, v);
  } else {
    for (int i = 0; i < J::nq; ++i) {
      q[i] = *get(i, false);
      v[i] = *get(i, true);
    }
  }
}

/// The variables a joint writes (write_internals) receive their value and
/// rate through set(i, value, rate), with value a scalar, a Vec3 or a Mat3.

/// The structural requirements of a joint type, checked one by one so that
/// a missing member is named (scene/joint_check.hpp).
namespace joint_requirements {
template <class J>
concept sizes = requires {
  { J::nq } -> std::convertible_to<int>;
  { J::nv } -> std::convertible_to<int>;
};
template <class J>
concept reversible = requires {
  { J::reversible } -> std::convertible_to<bool>;
};
template <class J>
concept neutral = requires(const J& j) { j.neutral(); };
template <class J>
concept motion = requires(const J& j, const double* q) { j.template motion<double, 1, true>(q); };
template <class J>
concept qdot = requires(const J& j, const double* q, const double* v, double* o) { j.qdot(q, v, o); };
/// The motion object's members (above), one by one.
template <class J>
using motion_of = decltype(std::declval<const J&>().template motion<double, 1, true>(std::declval<const double*>()));
template <class J>
concept motion_pose = requires(const motion_of<J>& m) {
  m.E;
  m.p;
};
template <class J>
concept motion_rates = requires(const motion_of<J>& m, const double* v) {
  m.w(v);
  m.pd(v);
};
template <class J>
concept motion_biases = requires(const motion_of<J>& m, const double* v) {
  m.w_bias(v);
  m.pd_bias(v);
};
template <class J>
concept motion_project = requires(const motion_of<J>& m, const svec<double, 7>& n) { m.project(n, n); };
template <class J>
concept motion_columns = requires(const motion_of<J>& m) { m.template col<0>(); };
template <class J>
concept motion_members =
    motion_pose<J> && motion_rates<J> && motion_biases<J> && motion_project<J> && motion_columns<J>;
template <class J>
concept planar_info = requires {
  { J::planar_normal() } -> std::convertible_to<int>;
  { J::moves_in_plane(0) } -> std::convertible_to<bool>;
};
template <class J>
concept reads_state = requires(const J& j, double* o) {
  j.read_state([](int, bool) -> const double* { return nullptr; }, o, o);
};
template <class J>
concept internals_io = requires(const J& j, const double* q, const double* v) {
  j.write_internals(q, v, [](int, const auto&, const auto&) {});
} && (plain_joint<J>() || reads_state<J>);
}  // namespace joint_requirements

template <class J>
concept Joint = Component<J> && J::kind == role::joint && joint_requirements::sizes<J> &&
                joint_requirements::reversible<J> && joint_requirements::neutral<J> && joint_requirements::motion<J> &&
                joint_requirements::motion_members<J> && joint_requirements::qdot<J> &&
                joint_requirements::planar_info<J> && joint_requirements::internals_io<J>;

}  // namespace flange
