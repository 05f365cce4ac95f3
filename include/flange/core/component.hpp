// What every component declares, and the vocabulary its equations are written in.
//
// A component is a type with
//   name          fixed_string, unique in a scene (it is in the type: Body<"mass">)
//   kind          its role in the scene's structure (world, joint, rigid edge,
//                 body, force element)
//   frames        the names of its frame connectors ("frame_a", "frame_b")
//   internals     its internal variables (φ, R_rel, v, ω …) with their kinds
//   equations()   its equations, as expression templates over the local
//                 variable slots declared here.
// Local slot numbering: frame k owns slots 4k..4k+3 (r, R, F, M); internal i is
// slot 4·(number of frames) + i. The scene maps slots to the flattened DAE
// vector; a component never knows where its variables live.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <type_traits>
#include <utility>

#include <Eigen/LU>

#include "flange/core/expr.hpp"
#include "flange/detail/always_false.hpp"
#include "flange/detail/fixed_string.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/errors.hpp"
#include "flange/math/types.hpp"

namespace flange {

enum class role { world, joint, rigid, body, force };

struct internal_decl {
  std::string_view name;
  expr::var_kind kind;
};

/// Frame variables of local frame K.
template <int K> inline constexpr expr::var<4 * K + 0, expr::var_kind::vec> r_{};
template <int K> inline constexpr expr::var<4 * K + 1, expr::var_kind::rot> R_{};
template <int K> inline constexpr expr::var<4 * K + 2, expr::var_kind::vec> F_{};
template <int K> inline constexpr expr::var<4 * K + 3, expr::var_kind::vec> M_{};
/// Internal variable I of a component with NF frames.
template <int NF, int I, expr::var_kind K> inline constexpr expr::var<4 * NF + I, K> internal_{};

template <class C>
concept Component = requires {
  { C::name.view() } -> std::convertible_to<std::string_view>;
  { C::kind } -> std::convertible_to<role>;
  C::frames.size();
  C::internals.size();
};

/// Does the component carry a body at its frame_a: a Body, or a rigid edge
/// with mass (BodyShape, BodyBox, BodyCylinder)? Such a component declares
/// m(), J() (about the centre of mass), r_cm(), inertia_about_frame(),
/// flows(k, g) (the wrench the body needs at frame_a for frame_a's motion k),
/// and has_cm_offset, is_point, is_diagonal, and its first two internals are
/// v and ω.
template <class C>
inline constexpr bool carries_body = requires { requires C::carries_body; };

/// The argument of a component's "all defaults" constructor,
/// C(std::initializer_list<all_defaults>), beside its default constructor:
/// with a default constructor alone, C({}) is ambiguous (the parameters from
/// {}, or a copy of C{}); an empty list converts to an initializer_list
/// exactly, so C({}) takes this one. C{}, C({}) and C are then all the
/// component with every parameter defaulted.
struct all_defaults {};

// ------------------------------------------------------------ inputs

/// The input type of a joint without a drive: it has no input, and its
/// dynamics have no input arithmetic at all.
struct undriven {};

/// The minimal state (joint coordinates q and rates v, in the order the joints
/// appear in the scene) as an input callable sees it: x.q(i), x.v(i). The
/// rates are v everywhere (initial_state's .v, v<"elbow">(x)); they are q̇
/// for one-axis joints, angular velocities where q holds a quaternion.
template <class T>
struct joint_state {
  const T* q_;
  const T* v_;
  int n;
  [[nodiscard]] T q(int i) const { return q_[i]; }
  [[nodiscard]] T v(int i) const { return v_[i]; }
  [[deprecated("flange: the rates are v: write x.v(i)")]] [[nodiscard]] T qd(int i) const { return v_[i]; }
};
/// A joint state of scalar T: joint_state<T> or the scene's named view of it
/// (scene/named_state.hpp), which inputs see so that they can read joints by name.
template <class X, class T>
concept state_of = std::is_base_of_v<joint_state<T>, X>;

/// The tag a drive shared by several joints receives: which joint asks.
/// decltype(tag)::name is the joint's name, usable as q<decltype(tag)::name>(x).
template <fixed_string Name>
struct joint_tag {
  static constexpr auto name = Name;
};
/// Joint Name's input from a drive shared by several joints: calls
/// drive(joint_tag<Name>{}, t, x), resolved at compile time (the URDF
/// scenes' make_scene(drive), tools/urdf/).
template <fixed_string Name, class Drive>
struct shared_drive {
  Drive drive;
  template <class T, class X>
  auto operator()(const T& t, const X& x) const {
    return drive(joint_tag<Name>{}, t, x);
  }
};
template <fixed_string Name, class Drive>
shared_drive<Name, Drive> drive_for(Drive drive) {
  return {std::move(drive)};
}

/// The parameter slot of an input whose type is a constant (a number or a
/// 3-vector, the default): it takes the value, or anything convertible to it,
/// and refuses a callable with one static_assert (Refuse<F>) that says how to
/// give the callable's type, instead of a page of conversion errors.
template <class V, template <class> class Refuse>
struct constant_input_slot {
  V value{};
  constant_input_slot() = default;
  template <class U>
    requires std::is_convertible_v<U&&, V>
  constant_input_slot(U&& u) : value(std::forward<U>(u)) {}  // NOLINT: implicit, as the value itself would be
  constant_input_slot(double x, double y, double z)
    requires std::is_same_v<V, Vec3d>
      : value(x, y, z) {}
  template <class U>
    requires(!std::is_convertible_v<U &&, V> && std::is_class_v<std::remove_cvref_t<U>>)
  constant_input_slot(U&&) {  // NOLINT
    (void)sizeof(Refuse<std::remove_cvref_t<U>>);
  }
};
/// The slot type for an input of type In: a constant_input_slot for numbers
/// and 3-vectors, the type itself for callables.
template <class In, template <class> class Refuse>
using input_slot = std::conditional_t<std::is_same_v<In, double> || std::is_same_v<In, Vec3d>,
                                      constant_input_slot<In, Refuse>, In>;
/// The input held in a slot.
template <class V, template <class> class R>
V&& take_input(constant_input_slot<V, R>&& s) {
  return std::move(s.value);
}
template <class In>
In&& take_input(In&& in) {
  return std::move(in);
}

/// Evaluates an input: a constant, a callable of time, or a callable of time
/// and joint state. Resolved at compile time; no virtual call, no std::function.
/// A constant input: a number or an Eigen vector (Eigen 3.4 objects are
/// "invocable" with an index, so they must be told apart from callables first).
template <class In>
inline constexpr bool is_constant_input = std::is_arithmetic_v<In> || std::is_base_of_v<Eigen::EigenBase<In>, In>;

template <class In>
struct input_written_for_double {
  static_assert(always_false<In>,
                "flange: this input is written for double, but the dynamics run on another scalar (dual numbers "
                "for a Jacobian, or long double); write it generic, [](auto t) or [](auto t, const auto& x)");
};

template <class T, class In, class X>
  requires state_of<X, T>
auto eval_input(const In& in, const T& t, const X& x) {
  if constexpr (is_constant_input<In>) return expr::detail::cast<T>(in);
  else if constexpr (std::is_invocable_v<const In&, const T&>) return expr::detail::cast<T>(in(t));
  else if constexpr (std::is_invocable_v<const In&, const T&, const X&>)
    return expr::detail::cast<T>(in(t, x));
  // Written for double only: one error, and a value of the input's own kind
  // (a number or a vector) so that nothing else fails after it.
  else if constexpr (std::is_invocable_v<const In&, double>) {
    (void)sizeof(input_written_for_double<In>);
    return expr::detail::cast<T>(std::invoke_result_t<const In&, double>{});
  } else if constexpr (std::is_invocable_v<const In&, double, const joint_state<double>&>) {
    (void)sizeof(input_written_for_double<In>);
    return expr::detail::cast<T>(std::invoke_result_t<const In&, double, const joint_state<double>&>{});
  } else static_assert(always_false<In>, "flange: an input is a number, an Eigen vector, a callable f(t) or f(t, x)");
}

/// Whether an input reads the joint state (a callable f(t, x)), not only the
/// time: a joint force with such an input depends on other joints'
/// coordinates (dynamics/derivatives.hpp differentiates a joint's own force
/// alone where none does).
template <class In>
inline constexpr bool input_reads_state = !is_constant_input<In> && !std::is_invocable_v<const In&, const double&>;

// ------------------------------------------------------------ validation

namespace detail {

/// Whether every entry is finite: a number, or a fixed-size Eigen matrix
/// entry by entry (Eigen's allFinite() builds expression templates that cost
/// a small unit a tenth of a second to compile).
template <class V>
bool all_finite(const V& v) {
  if constexpr (std::is_arithmetic_v<V>) {
    return std::isfinite(v);
  } else {
    for (int j = 0; j < int(v.cols()); ++j)
      for (int i = 0; i < int(v.rows()); ++i)
        if (!std::isfinite(v(i, j))) return false;
    return true;
  }
}

/// Whether every entry of a fixed-size Eigen matrix is zero.
template <class V>
bool all_zero(const V& v) {
  for (int j = 0; j < int(v.cols()); ++j)
    for (int i = 0; i < int(v.rows()); ++i)
      if (v(i, j) != 0) return false;
  return true;
}

template <class V>
void require_finite(std::string_view component, std::string_view kind, std::string_view what, const V& v) {
  if (!all_finite(v))
    throw parameter_error(concat(kind, " \"", component, "\": parameter ", what, " is not finite (", v, ")"));
}
FLANGE_COMMON(void require_finite<double>(std::string_view, std::string_view, std::string_view, const double&))
FLANGE_COMMON(void require_finite<Vec3d>(std::string_view, std::string_view, std::string_view, const Vec3d&))
FLANGE_COMMON(void require_finite<Mat3d>(std::string_view, std::string_view, std::string_view, const Mat3d&))

/// A unit axis from a user vector: finite and non-zero, then normalised (as
/// Modelica normalises a joint axis). The vector is first divided by its
/// largest component, so that no length overflows or underflows: any finite
/// direction from 1e-300 to 1e300 long is accepted.
FLANGE_LAZY
Vec3d unit_axis(std::string_view component, std::string_view kind, const Vec3d& n) {
  require_finite(component, kind, "n (axis)", n);
  const double big = n.cwiseAbs().maxCoeff();
  if (!(big > 0))
    throw parameter_error(concat(kind, " \"", component, "\": axis n = [", n.transpose(),
                                 "] is zero; give a non-zero direction"));
  const Vec3d u = n / big;
  return u / u.norm();
}
FLANGE_COMMON(Vec3d unit_axis<0>(std::string_view, std::string_view, const Vec3d&))

/// A rotation matrix: finite, orthogonal and right-handed (to 1e-9).
FLANGE_LAZY
void require_rotation(std::string_view component, std::string_view kind, std::string_view what,
                      const Mat3d& R) {
  require_finite(component, kind, what, R);
  const double err = (R * R.transpose() - Mat3d::Identity()).cwiseAbs().maxCoeff();
  if (err > 1e-9 || R.determinant() < 0)
    throw parameter_error(concat(kind, " \"", component, "\": ", what, " = [", R, "] is not a rotation (|R·R' − 1| = ",
                                 err, ", det R = ", R.determinant(), "); give an orthogonal, right-handed matrix, or use orientation::axis_angle, "
                                 "cardan or rpy"));
}
FLANGE_COMMON(void require_rotation<0>(std::string_view, std::string_view, std::string_view, const Mat3d&))

/// The eigenvalues of a symmetric 3×3 matrix, ascending: cyclic Jacobi
/// rotations until the off-diagonal entries vanish against the diagonal
/// (each eigenvalue to about 1e-16 of the largest; a few sweeps).
FLANGE_LAZY
Vec3d symmetric_eigenvalues(const Mat3d& A) {
  double a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = (A(i, j) + A(j, i)) / 2;
  constexpr int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < 32; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-36 * diag)) break;
    for (const auto& pq : pairs) {
      const int p = pq[0], q = pq[1], r = 3 - p - q;
      if (a[p][q] == 0) continue;
      const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
      const double t = std::abs(theta) > 1e150 ? 1 / (2 * theta)
                                               : (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
      const double c = 1 / std::sqrt(t * t + 1), sn = t * c;
      a[p][p] -= t * a[p][q];
      a[q][q] += t * a[p][q];
      a[p][q] = a[q][p] = 0;
      const double arp = a[r][p], arq = a[r][q];
      a[r][p] = a[p][r] = c * arp - sn * arq;
      a[r][q] = a[q][r] = sn * arp + c * arq;
    }
  }
  Vec3d lam(a[0][0], a[1][1], a[2][2]);
  if (lam(0) > lam(1)) std::swap(lam(0), lam(1));
  if (lam(1) > lam(2)) std::swap(lam(1), lam(2));
  if (lam(0) > lam(1)) std::swap(lam(0), lam(1));
  return lam;
}
FLANGE_COMMON(Vec3d symmetric_eigenvalues<0>(const Mat3d&))

/// A physical inertia tensor: finite, symmetric, positive semi-definite, and
/// its principal moments obey the triangle inequality, to 1e-12 of J's
/// largest entry.
FLANGE_LAZY
void require_inertia(std::string_view component, std::string_view kind, const Mat3d& J) {
  require_finite(component, kind, "J (inertia)", J);
  const double scale = std::max(J.cwiseAbs().maxCoeff(), 1e-300);
  if ((J - J.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    throw parameter_error(concat(kind, " \"", component, "\": inertia J = [", J, "] is not symmetric"));
  const Vec3d lam = symmetric_eigenvalues(J);
  const double tol = 1e-12 * scale;
  if (lam(0) < -tol)
    throw parameter_error(concat(kind, " \"", component, "\": inertia J = [", J,
                                 "] is not positive semi-definite (smallest principal moment ", lam(0), ")"));
  if (lam(2) > lam(0) + lam(1) + tol)
    throw parameter_error(concat(kind, " \"", component, "\": inertia J = [", J,
                                 "] breaks the triangle inequality: principal moment ", lam(2),
                                 " exceeds the sum of the other two (", lam(0) + lam(1), ")"));
}
FLANGE_COMMON(void require_inertia<0>(std::string_view, std::string_view, const Mat3d&))

}  // namespace detail
}  // namespace flange
