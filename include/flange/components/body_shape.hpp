// BodyShape: a rigid body at frame_a and a second frame frame_b at r from
// it, as Modelica's BodyShape (a Body and a FixedTranslation in one). The
// body has mass m, inertia I about its centre of mass r_CM (both in frame_a
// coordinates):
//
//   v = ṙ₁                        r₂ = r₁ + R₁'·r
//   ω̃ = R₁·Ṙ₁'                    R₂ = R₁
//   F₁ = m·(R₁·(v̇ − g) + ω̇ × r_CM + ω × (ω × r_CM)) − F₂
//   M₁ = I·ω̇ + ω × (I·ω) + r_CM × F_body − M₂ − r × F₂
//
// (F_body the first line's body term.) A rigid edge of the kinematic tree
// that carries mass: the dynamics fold its body into the link of frame_a.
//
// BodyBox and BodyCylinder compute m, I and r_CM from their shape, as
// Modelica's: a box of length |r| along r (width along the width direction,
// height across both), or a cylinder of length |r| along r with an outer
// and an optional inner diameter, of density ρ (default 7700 kg/m³, steel),
// the centre of mass at r/2. Width (and diameter) default to |r|/20, height
// to the width, as in Modelica.
#pragma once
#include <numbers>
#include <string>

#include <boost/hana/tuple.hpp>

#include "flange/components/body.hpp"
#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/lazy.hpp"

namespace flange {

namespace shape_kind {
struct none {};      ///< BodyShape: m, I and r_CM given
struct box {};       ///< BodyBox
struct cylinder {};  ///< BodyCylinder
}  // namespace shape_kind

namespace detail {

/// The shape frame's axes (rows) in frame_a: x along n, y toward y_hint
/// (Modelica's Frames.from_nxy; another hint if y_hint is parallel to n).
FLANGE_LAZY
Mat3d shape_axes(const Vec3d& n, const Vec3d& y_hint) {
  const Vec3d ex = n.normalized();
  Vec3d ez = ex.cross(y_hint);
  if (ez.norm() <= 1e-6 * y_hint.norm()) {
    // y_hint ∥ n: Modelica's rule, a coordinate axis not along n.
    const Vec3d alt = std::abs(ex.x()) > 0.9 ? Vec3d(0, 1, 0) : Vec3d(1, 0, 0);
    ez = ex.cross(alt);
  }
  ez.normalize();
  Mat3d T;
  T.row(0) = ex;
  T.row(1) = ez.cross(ex);
  T.row(2) = ez;
  return T;
}
FLANGE_COMMON(Mat3d shape_axes<0>(const Vec3d&, const Vec3d&))

/// The body of a shape: m, I about the centre (frame_a axes), r_CM, and the
/// shape's sizes for drawing.
struct shaped_body {
  double m;
  Mat3d I;
  Vec3d r_cm;
  Vec3d size;  ///< box: length, width, height; cylinder: length, diameter, inner diameter
  Mat3d axes = Mat3d::Identity();  ///< the shape's axes (rows: along r, width, height) in frame_a
};

}  // namespace detail

template <fixed_string Name, class Shape = shape_kind::none>
class BodyShape {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = std::is_same_v<Shape, shape_kind::box>        ? "BodyBox"
                                                : std::is_same_v<Shape, shape_kind::cylinder> ? "BodyCylinder"
                                                                                         : "BodyShape";
  static constexpr role kind = role::rigid;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 2> internals{
      {{"v", expr::var_kind::vec}, {"ω", expr::var_kind::vec}}};
  static constexpr bool carries_body = true;
  static constexpr bool has_cm_offset = true, is_point = false, is_diagonal = false;
  using shape_type = Shape;

  /// BodyShape: frame_b at r; mass m, inertia I about the centre of mass
  /// r_CM, in frame_a.
  struct shape_params {
    Vec3d r;
    Vec3d r_cm = Vec3d::Zero();
    double m = 0;
    Mat3d I = Mat3d::Zero();
  };
  /// BodyBox: frame_b at r, the box along r; width and height (0: |r|/20
  /// and the width), the width direction, the density.
  struct box_params {
    Vec3d r;
    double width = 0;
    double height = 0;
    Vec3d width_direction = Vec3d(0, 1, 0);
    double density = 7700;
  };
  /// BodyCylinder: frame_b at r, the cylinder along r; diameter (0: |r|/20),
  /// inner diameter (a tube), density.
  struct cylinder_params {
    Vec3d r;
    double diameter = 0;
    double inner_diameter = 0;
    double density = 7700;
  };
  using params = std::conditional_t<std::is_same_v<Shape, shape_kind::box>, box_params,
                                    std::conditional_t<std::is_same_v<Shape, shape_kind::cylinder>, cylinder_params,
                                                       shape_params>>;

  explicit BodyShape(params p) : r_b_(p.r) {
    require_finite(p);
    body_ = make(p);
    if (!(body_.m >= 0) || !std::isfinite(body_.m))
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": mass m = ", body_.m,
                                           " is negative or not finite"));
    detail::require_inertia(name.view(), type_name, body_.I);
  }

  [[nodiscard]] double m() const { return body_.m; }
  [[nodiscard]] const Mat3d& J() const { return body_.I; }
  [[nodiscard]] const Vec3d& r_cm() const { return body_.r_cm; }
  /// frame_b's origin seen from frame_a, in frame_a coordinates.
  [[nodiscard]] const Vec3d& r() const { return r_b_; }
  /// The shape's sizes (box: length, width, height; cylinder: length,
  /// diameter, inner diameter; BodyShape: zero), for drawing.
  [[nodiscard]] const Vec3d& size() const { return body_.size; }
  /// The shape's axes in frame_a (rows: along r, then the width's and the
  /// height's directions; a cylinder's last two across its axis).
  [[nodiscard]] const Mat3d& axes() const { return body_.axes; }
  [[nodiscard]] Mat3d inertia_about_frame() const { return detail::inertia_about_origin(body_.m, body_.I, body_.r_cm); }
  /// The wrench the body needs at frame_a for frame_a's motion k (its
  /// share of F₁, M₁; recovery adds what frame_b passes on).
  template <class T>
  [[nodiscard]] wrench<T> flows(const frame_kinematics<T>& k, const Vec3<T>& g) const {
    return detail::body_wrench(body_.m, body_.I, body_.r_cm, k, g);
  }

  static constexpr auto v = internal_<2, 0, expr::var_kind::vec>;
  static constexpr auto w = internal_<2, 1, expr::var_kind::vec>;

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<double> m{body_.m, "m"};
    const param<Mat3d> I{body_.I, "I"};
    const param<Vec3d> c{body_.r_cm, "r_CM"};
    const param<Vec3d> r{r_b_, "r"};
    return boost::hana::make_tuple(
        eq(v, der(r_<0>)),                                 //
        skew_eq(tilde(w), R_<0> * transpose(der(R_<0>))),  //
        eq(r_<1>, r_<0> + transpose(R_<0>) * r),           //
        orientation_eq(R_<1>, R_<0>),                      //
        eq(F_<0>, flange::detail::body_force(v, w, m, c) - F_<1>),
        eq(M_<0>, flange::detail::body_moment(w, I, c, flange::detail::body_force(v, w, m, c)) - M_<1> - cross(r, F_<1>)));
  }

  /// A rigid edge: frame_b's constant pose in frame_a, without rotation.
  static constexpr int rotation_axis = -2;
  template <class T>
  [[nodiscard]] pose<T> relative_pose() const {
    return {Mat3<T>::Identity(), r_b_.cast<T>()};
  }

 private:
  void require_finite(const params& p) const {
    detail::require_finite(name.view(), type_name, "r", p.r);
    if constexpr (!std::is_same_v<Shape, shape_kind::none>) {
      if (!(p.r.norm() > 0))
        throw parameter_error(detail::concat(type_name, " \"", name.view(),
                                             "\": r = [", p.r.transpose(), "] has no length, so the shape has no axis"));
      detail::require_finite(name.view(), type_name, "density", p.density);
      if (p.density < 0)
        throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": density ", p.density, " is negative"));
    }
  }
  static void require_size(double value, const char* what) {
    if (!std::isfinite(value) || value < 0)
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": ", what, " ", value,
                                           " is negative or not finite"));
  }
  static detail::shaped_body make(const shape_params& p) {
    detail::require_finite(name.view(), type_name, "r_cm", p.r_cm);
    detail::require_finite(name.view(), type_name, "m (mass)", p.m);
    return {p.m, p.I, p.r_cm, Vec3d::Zero()};
  }
  static detail::shaped_body make(const box_params& p) {
    const double l = p.r.norm();
    const double w = p.width > 0 ? p.width : l / 20, h = p.height > 0 ? p.height : w;
    require_size(p.width, "width");
    require_size(p.height, "height");
    detail::require_finite(name.view(), type_name, "width_direction", p.width_direction);
    const double m = p.density * l * w * h;
    const Vec3d D(m * (w * w + h * h) / 12, m * (l * l + h * h) / 12, m * (l * l + w * w) / 12);
    const Mat3d T = detail::shape_axes(p.r, p.width_direction);
    return {m, T.transpose() * D.asDiagonal() * T, p.r / 2, Vec3d(l, w, h), T};
  }
  static detail::shaped_body make(const cylinder_params& p) {
    const double l = p.r.norm();
    const double d = p.diameter > 0 ? p.diameter : l / 20, di = p.inner_diameter;
    require_size(p.diameter, "diameter");
    require_size(di, "inner diameter");
    if (di >= d)
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": inner diameter ", di,
                                           " is not smaller than the diameter ", d));
    const double ro = d / 2, ri = di / 2;
    const double mo = p.density * std::numbers::pi * l * ro * ro, mi = p.density * std::numbers::pi * l * ri * ri;
    const double axial = (mo * ro * ro - mi * ri * ri) / 2;
    const double across = (mo * (l * l + 3 * ro * ro) - mi * (l * l + 3 * ri * ri)) / 12;
    const Mat3d T = detail::shape_axes(p.r, Vec3d(0, 1, 0));
    return {mo - mi, T.transpose() * Vec3d(axial, across, across).asDiagonal() * T, p.r / 2, Vec3d(l, d, di), T};
  }

  Vec3d r_b_;
  detail::shaped_body body_;
};

/// Modelica's BodyBox: a box from frame_a to frame_b (at r).
template <fixed_string Name>
using BodyBox = BodyShape<Name, shape_kind::box>;
/// Modelica's BodyCylinder: a cylinder (or a tube) from frame_a to frame_b (at r).
template <fixed_string Name>
using BodyCylinder = BodyShape<Name, shape_kind::cylinder>;

}  // namespace flange
