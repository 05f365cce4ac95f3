// Body: a rigid body of mass m and inertia J at frame_a.
//
//   v = ṙ₁                   F₁ = R₁·m·(v̇ − g)
//   ω̃ = R₁·Ṙ₁'               M₁ = J·ω̇ + ω × (J·ω)
//
// v (world coordinates) and ω (frame coordinates) are internal variables; g
// is the World's gravity. F₁, M₁ are the cut force and torque the connection
// exerts on the body, in frame_a coordinates.
//
// Body<Name, cm::offset> adds Modelica's centre-of-mass offset r_CM (frame_a
// coordinates; J is then about the centre of mass, resolved in frame_a):
//
//   F₁ = m·(R₁·(v̇ − g) + ω̇ × r_CM + ω × (ω × r_CM))
//   M₁ = J·ω̇ + ω × (J·ω) + r_CM × F₁
//
// Body<Name, cm::at_frame, inertia_kind::point>, or PointMass<Name>, is a mass
// without rotational inertia (Modelica's PointMass): J = 0 by its type, and
//
//   M₁ = 0
//
// The body still has ω (its frame turns with whatever it is fixed to), so its
// variables and its equation count are those of Body.
//
// Body<Name, cm::at_frame, inertia_kind::diagonal> declares J diagonal in
// frame_a's axes (checked at construction). Where a link's bodies all sit at
// its origin, the dynamics then know its inertia is diagonal, or zero for
// point masses, and skip the products that rules out (dynamics/algebra.hpp).
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace cm {
struct at_frame {};  ///< the centre of mass is at frame_a (the paper's Body)
struct offset {};    ///< the centre of mass is at r_CM from frame_a
}  // namespace cm

namespace inertia_kind {
struct full {};      ///< a rotational inertia J (the paper's Body)
struct diagonal {};  ///< J diagonal in frame_a's axes (checked at construction)
struct point {};     ///< no rotational inertia: a point mass
}  // namespace inertia_kind

namespace detail {
/// A body's equations at frame_a, written once for Body and BodyShape: the
/// force F = m·(R₁·(v̇ − g) + ω̇ × r_CM + ω × (ω × r_CM)) and the moment
/// J·ω̇ + ω × (J·ω) + r_CM × F it needs, over its internals v and ω.
template <class V, class W, class M, class C>
auto body_force(const V& v, const W& w, const M& m, const C& c) {
  using namespace expr;
  return m * (R_<0> * (der(v) - gravity{}) + cross(der(w), c) + cross(w, cross(w, c)));
}
template <class W, class J, class C, class F>
auto body_moment(const W& w, const J& I, const C& c, const F& f) {
  using namespace expr;
  return I * der(w) + cross(w, I * w) + cross(c, f);
}
/// The same as numbers, for a given motion of frame_a (recovery).
template <class T>
wrench<T> body_wrench(double m, const Mat3d& J, const Vec3d& r_cm, const frame_kinematics<T>& k, const Vec3<T>& g) {
  const Mat3<T> I = J.cast<T>();
  const Vec3<T> c = r_cm.cast<T>();
  const Vec3<T> F = T(m) * (k.R * (k.a - g) + k.wd.cross(c) + k.w.cross(k.w.cross(c)));
  return {F, I * k.wd + k.w.cross(I * k.w) + c.cross(F)};
}
FLANGE_COMMON(wrench<double> body_wrench<double>(double, const Mat3d&, const Vec3d&, const frame_kinematics<double>&,
                                                 const Vec3<double>&))
/// Mass m, inertia J about the centre of mass and the centre r_CM, all in
/// frame_a: the inertia about frame_a's origin.
FLANGE_LAZY
Mat3d inertia_about_origin(double m, const Mat3d& J, const Vec3d& r_cm) {
  const Mat3d c = tilde<double>(r_cm);
  return J - m * c * c;
}
FLANGE_COMMON(Mat3d inertia_about_origin<0>(double, const Mat3d&, const Vec3d&))
/// A Body's parameters checked: the mass finite and non-negative, J a
/// physical inertia (diagonal for inertia_kind::diagonal, zero for a point
/// mass), r_cm finite and zero unless the body is declared cm::offset. A
/// function of its own, compiled once per unit that calls it (FLANGE_LAZY)
/// rather than once per body type.
FLANGE_LAZY
void check_body(std::string_view name, bool diagonal, bool point, bool cm_offset, double m, const Mat3d& J,
                const Vec3d& r_cm) {
  require_finite(name, "Body", "m (mass)", m);
  if (m < 0) throw parameter_error(concat("Body \"", name, "\": mass m = ", m, " is negative"));
  require_inertia(name, "Body", J);
  if (diagonal && (J(0, 1) != 0 || J(0, 2) != 0 || J(1, 0) != 0 || J(1, 2) != 0 || J(2, 0) != 0 || J(2, 1) != 0))
    throw parameter_error(concat("Body \"", name, "\": declared with a diagonal inertia, but J = [", J,
                                 "] has products of inertia; use inertia_kind::full"));
  if (point && !all_zero(J))
    throw parameter_error(concat("Body \"", name, "\": a point mass has no rotational inertia, but J = [", J,
                                 "] was given; leave J out, or make it a Body with inertia_kind::full"));
  require_finite(name, "Body", "r_cm", r_cm);
  if (!cm_offset && !all_zero(r_cm))
    throw parameter_error(concat("Body \"", name, "\": r_cm = [", r_cm, "] is not zero; declare the body as Body<\"",
                                 name, "\", cm::offset> to give it a centre-of-mass offset"));
}
FLANGE_COMMON(void check_body<0>(std::string_view, bool, bool, bool, double, const Mat3d&, const Vec3d&))
}  // namespace detail

template <fixed_string Name, class CM = cm::at_frame, class Inertia = inertia_kind::full>
class Body {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Body";
  static constexpr role kind = role::body;
  static constexpr std::array<std::string_view, 1> frames{"frame_a"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"v", expr::var_kind::vec}, {"ω", expr::var_kind::vec}}};
  static constexpr bool carries_body = true;  ///< has mass at frame_a (core/component.hpp)
  static constexpr bool has_cm_offset = std::is_same_v<CM, cm::offset>;
  static constexpr bool is_point = std::is_same_v<Inertia, inertia_kind::point>;
  static constexpr bool is_diagonal = std::is_same_v<Inertia, inertia_kind::diagonal>;
  static_assert(!(is_point && has_cm_offset),
                "flange: a point mass sits at its frame; attach it through a FixedTranslation instead of cm::offset");

  struct params {
    double m;
    Mat3d J = Mat3d::Zero();
    Vec3d r_cm = Vec3d::Zero();
  };

  explicit Body(params p) : m_(p.m), J_(p.J), r_cm_(p.r_cm) {
    detail::check_body(name.view(), is_diagonal, is_point, has_cm_offset, m_, J_, r_cm_);
  }

  [[nodiscard]] double m() const { return m_; }
  [[nodiscard]] const Mat3d& J() const { return J_; }
  [[nodiscard]] const Vec3d& r_cm() const { return r_cm_; }

  static constexpr auto v = internal_<1, 0, expr::var_kind::vec>;
  static constexpr auto w = internal_<1, 1, expr::var_kind::vec>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<double> m{m_, "m"};
    const param<Mat3d> J{J_, "J"};
    if constexpr (is_point) {
      return boost::hana::make_tuple(eq(v, der(r_<0>)),                                 //
                                     skew_eq(tilde(w), R_<0> * transpose(der(R_<0>))),  //
                                     eq(F_<0>, R_<0> * m * (der(v) - gravity{})),       //
                                     eq(M_<0>, zero<shape::vec>{}));
    } else if constexpr (!has_cm_offset) {
      return boost::hana::make_tuple(eq(v, der(r_<0>)),                                    //
                                     skew_eq(tilde(w), R_<0> * transpose(der(R_<0>))),     //
                                     eq(F_<0>, R_<0> * m * (der(v) - gravity{})),          //
                                     eq(M_<0>, J * der(w) + cross(w, J * w)));
    } else {
      const param<Vec3d> c{r_cm_, "r_CM"};
      return boost::hana::make_tuple(eq(v, der(r_<0>)),                                 //
                                     skew_eq(tilde(w), R_<0> * transpose(der(R_<0>))),  //
                                     eq(F_<0>, flange::detail::body_force(v, w, m, c)),          //
                                     eq(M_<0>, flange::detail::body_moment(w, J, c, F_<0>)));
    }
  }

  /// Mass, first moment h = m·r_CM and inertia about frame_a's origin, all in
  /// frame_a coordinates: the body's spatial inertia.
  [[nodiscard]] Mat3d inertia_about_frame() const { return detail::inertia_about_origin(m_, J_, r_cm_); }

  /// The cut force and torque on the body (frame_a coordinates) for a given
  /// motion of frame_a: the right-hand sides of the equations above.
  template <class T>
  [[nodiscard]] wrench<T> flows(const frame_kinematics<T>& k, const Vec3<T>& g) const {
    if constexpr (is_point) {
      return {T(m_) * (k.R * (k.a - g)), Vec3<T>::Zero()};
    } else {
      return detail::body_wrench(m_, J_, r_cm_, k, g);
    }
  }

 private:
  double m_;
  Mat3d J_;
  Vec3d r_cm_;
};

/// A point mass: Body without rotational inertia (Modelica's PointMass).
template <fixed_string Name>
using PointMass = Body<Name, cm::at_frame, inertia_kind::point>;

}  // namespace flange
