// Closed-loop mechanisms with closed forms: the four-bar linkage (Grashof
// crank-rocker, parallelogram), the slider-crank and a row of parallelogram
// windows, planar about z, each with the closed-form kinematics its tests,
// examples and benchmarks compare against.
//
//   four-bar:     O2 ──crank a── A ──coupler b── B ──rocker c── O4, O4 = (d, 0)
//   slider-crank: O ──crank r── A ──rod l── P, P on the x axis
//   window row:   N + 1 posts on the ground line, N top bars between their tips
//
// Bars are uniform: mass m at the middle, I = m·L²/12 about it. Each loop
// is closed by the joint written last ("rocker_pivot", "wrist_pin", "top_end<i>"), which
// is cut (docs/loops.md); the state holds the tree's joints.
#pragma once
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "flange/components/body.hpp"
#include "flange/components/body_shape.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

/// A uniform bar of length L and mass m along x, frame_b at its end.
template <fixed_string Name>
auto bar(double L, double m) {
  Mat3d I = Mat3d::Zero();
  I(1, 1) = I(2, 2) = m * L * L / 12;
  I(0, 0) = 1e-3 * I(1, 1);  // a thin bar: a little inertia about its own axis
  return BodyShape<Name>({.r = Vec3d(L, 0, 0), .r_cm = Vec3d(L / 2, 0, 0), .m = m, .I = I});
}

struct fourbar_params {
  double ground = 1.0, crank = 0.3, coupler = 1.0, rocker = 0.8;  ///< d, a, b, c [m]
  double m_crank = 1.0, m_coupler = 2.0, m_rocker = 1.5;           ///< [kg]
  Vec3d g = Vec3d(0, -9.81, 0);
};

/// The four-bar: the crank turns about O2 (joint "crank_pivot", q = θ2, the
/// crank's angle from the ground line), then "crank_pin" (coupler relative
/// to crank) and "rocker_pin" (rocker relative to coupler); "rocker_pivot"
/// closes the loop at O4 and is cut. (Params is a template parameter so
/// that the scene is instantiated only where fourbar is called.)
template <class Axis = axis::z, class Params = fourbar_params>
auto fourbar(const Params& p) {
  return scene(World<"world">({.g = p.g}),                                                     //
               Revolute<"crank_pivot", Axis>{}, bar<"crank">(p.crank, p.m_crank),  //
               Revolute<"crank_pin", Axis>{}, bar<"coupler">(p.coupler, p.m_coupler),
               Revolute<"rocker_pin", Axis>{}, bar<"rocker">(p.rocker, p.m_rocker),
               FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}), Revolute<"rocker_pivot", Axis>{},
               connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
               connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
               connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "rocker_pivot.frame_a">,
               connect<"rocker.frame_b", "rocker_pivot.frame_b">);
}

/// Freudenstein's equation for the rocker angle θ4 (at O4, from the ground
/// line) given the crank angle θ2: K1·cos θ4 − K2·cos θ2 + K3 = cos(θ2 − θ4).
/// Returns its solution on the open branch (B above the line O2–O4 for the
/// default lengths at θ2 = π/2), or throws if the loop cannot close at θ2.
inline double freudenstein_rocker(const fourbar_params& p, double theta2) {
  const double a = p.crank, b = p.coupler, c = p.rocker, d = p.ground;
  const double K1 = d / a, K2 = d / c, K3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
  const double A = std::cos(theta2) - K1 - K2 * std::cos(theta2) + K3;
  const double B = -2 * std::sin(theta2);
  const double C = K1 - (K2 + 1) * std::cos(theta2) + K3;
  const double disc = B * B - 4 * A * C;
  if (disc < 0) throw std::domain_error("four-bar: the loop cannot close at this crank angle");
  return 2 * std::atan2(-B - std::sqrt(disc), 2 * A);
}

/// The four-bar's tree coordinates q = (θ2, θ3 − θ2, θ4 + π − θ3) with θ3 the
/// coupler's angle, from θ2 and θ4.
inline std::array<double, 3> fourbar_coordinates(const fourbar_params& p, double theta2, double theta4) {
  const double ax = p.crank * std::cos(theta2), ay = p.crank * std::sin(theta2);
  const double bx = p.ground + p.rocker * std::cos(theta4), by = p.rocker * std::sin(theta4);
  const double theta3 = std::atan2(by - ay, bx - ax);
  return {theta2, theta3 - theta2, theta4 + std::numbers::pi - theta3};
}

/// The free four-bar's equation of motion in its one coordinate, the crank
/// angle θ2, written by hand (Lagrange with the loop closed in closed form):
///
///   J(θ2)·θ̈2 + ½·J'(θ2)·θ̇2² + V'(θ2) = 0,
///   J = I2 + I3·k3² + m3·|∂r_G3/∂θ2|² + I4·k4²,
///
/// with k3 = θ̇3/θ̇2 and k4 = θ̇4/θ̇2 from the velocity loop, their derivatives
/// from the acceleration loop, I2 and I4 about the pivots, I3 about the
/// coupler's centre. On the open branch (freudenstein_rocker). Returns θ̈2.
inline double fourbar_crank_acceleration(const fourbar_params& p, double th2, double w2) {
  using std::cos;
  using std::sin;
  const double a = p.crank, b = p.coupler, c = p.rocker, d = p.ground, g = -p.g.y();
  const double th4 = freudenstein_rocker(p, th2);
  const double ax = a * cos(th2), ay = a * sin(th2);
  const double th3 = std::atan2(c * sin(th4) - ay, d + c * cos(th4) - ax);
  const double s2 = sin(th2), c2 = cos(th2), s3 = sin(th3), c3 = cos(th3), s4 = sin(th4), c4 = cos(th4);
  // Velocity loop a·i·e^{iθ2} + b·k3·i·e^{iθ3} = c·k4·i·e^{iθ4}, per unit θ̇2.
  const double den = sin(th4 - th3);
  const double k3 = a * sin(th2 - th4) / (b * den), k4 = a * sin(th2 - th3) / (c * den);
  // Acceleration loop at θ̈2 = 0, per unit θ̇2²: b·k3'·i·e^{iθ3} − c·k4'·i·e^{iθ4}
  //   = a·e^{iθ2} + b·k3²·e^{iθ3} − c·k4²·e^{iθ4} (real and imaginary parts).
  const double rx = a * c2 + b * k3 * k3 * c3 - c * k4 * k4 * c4;
  const double ry = a * s2 + b * k3 * k3 * s3 - c * k4 * k4 * s4;
  // [−b·s3, c·s4; b·c3, −c·c4]·(k3', k4') = (rx, ry)
  const double m11 = -b * s3, m12 = c * s4, m21 = b * c3, m22 = -c * c4, det = m11 * m22 - m12 * m21;
  const double k3d = (rx * m22 - m12 * ry) / det, k4d = (m11 * ry - rx * m21) / det;
  const double I2 = p.m_crank * a * a / 3, I3 = p.m_coupler * b * b / 12, I4 = p.m_rocker * c * c / 3;
  // The coupler's centre: r_G3 = A + (b/2)·e^{iθ3}; its velocity and that velocity's θ2-derivative.
  const double vx = -a * s2 - b / 2 * k3 * s3, vy = a * c2 + b / 2 * k3 * c3;
  const double vxd = -a * c2 - b / 2 * (k3d * s3 + k3 * k3 * c3), vyd = -a * s2 + b / 2 * (k3d * c3 - k3 * k3 * s3);
  const double J = I2 + I3 * k3 * k3 + p.m_coupler * (vx * vx + vy * vy) + I4 * k4 * k4;
  const double Jd = 2 * (I3 * k3 * k3d + p.m_coupler * (vx * vxd + vy * vyd) + I4 * k4 * k4d);
  const double Vd = g * (p.m_crank * a / 2 * c2 + p.m_coupler * vy + p.m_rocker * c / 2 * c4 * k4);
  return -(0.5 * Jd * w2 * w2 + Vd) / J;
}

struct slider_crank_params {
  double crank = 0.1, rod = 0.35;        ///< r, l [m]
  double m_crank = 1.0, m_rod = 0.5, m_piston = 0.8;
  Vec3d g = Vec3d(0, -9.81, 0);
};

/// The slider-crank: the crank turns about O (joint "crank_pivot", q = θ),
/// the rod about the crank pin ("crank_pin", relative), the piston slides
/// along x ("slide", q = its x); "wrist_pin" joins rod and piston and is cut.
/// (A template whose body depends on its parameter, as every scene factory
/// here: otherwise the scene's type, its model and its dynamics would be
/// built in every unit that includes flange.hpp, used or not.)
template <class Params = slider_crank_params>
auto slider_crank(const Params& p) {
  return scene(World<"world">({.g = p.g}),                                                            //
               Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),      //
               Revolute<"crank_pin", axis::z>{}, bar<"rod">(p.rod, p.m_rod),              //
               Prismatic<"slide", axis::x>({}), Body<"piston">({.m = p.m_piston}),                   //
               Revolute<"wrist_pin", axis::z>{},                                                     //
               connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "rod.frame_a">,
               connect<"world.frame_b", "slide.frame_a">, connect<"slide.frame_b", "piston.frame_a">,
               connect<"rod.frame_b", "wrist_pin.frame_a">, connect<"slide.frame_b", "wrist_pin.frame_b">);
}

struct window_row_params {
  double width = 0.5, height = 1.0;     ///< the windows' pitch w along x and the posts' length h [m]
  double m_post = 1.0, m_top = 0.5;     ///< [kg]
  Vec3d g = Vec3d(0, -9.81, 0);
  Vec3d axis = Vec3d(0, 0, 1);          ///< every joint's axis, with window_row's Axis = axis::any (⟂ x)
};

/// A revolute of window_row: the typed Axis, or about p.axis at run time.
template <fixed_string Name, class Axis, class Params>
auto window_joint(const Params& p) {
  if constexpr (std::is_same_v<Axis, axis::any>) return Revolute<Name, Axis>({.n = p.axis});
  else return Revolute<Name, Axis>{};
}

/// window_row's components and connections, as a structure without
/// dynamics (detail::scene_structure).
template <int N, class Params, class Axis>
auto window_row_structure(const Params& p) {
  static_assert(N >= 1, "window_row<N>: at least one window");
  return [&]<int... I, int... K>(std::integer_sequence<int, I...>, std::integer_sequence<int, K...>) {
    return flange::detail::scene_structure(
        World<"world">({.g = p.g}), FixedTranslation<indexed_name<"ground", I>()>({.d = Vec3d(I * p.width, 0, 0)})...,
        window_joint<indexed_name<"post_pivot", I>(), Axis>(p)..., bar<indexed_name<"post", I>()>(p.height, p.m_post)...,
        window_joint<indexed_name<"top_pin", K>(), Axis>(p)..., bar<indexed_name<"top", K>()>(p.width, p.m_top)...,
        window_joint<indexed_name<"top_end", K>(), Axis>(p)...,
        connect<"world.frame_b", indexed_name<"ground", I>() + ".frame_a">...,
        connect<indexed_name<"ground", I>() + ".frame_b", indexed_name<"post_pivot", I>() + ".frame_a">...,
        connect<indexed_name<"post_pivot", I>() + ".frame_b", indexed_name<"post", I>() + ".frame_a">...,
        connect<indexed_name<"post", K>() + ".frame_b", indexed_name<"top_pin", K>() + ".frame_a">...,
        connect<indexed_name<"top_pin", K>() + ".frame_b", indexed_name<"top", K>() + ".frame_a">...,
        connect<indexed_name<"top", K>() + ".frame_b", indexed_name<"top_end", K>() + ".frame_a">...,
        connect<indexed_name<"post", K + 1>() + ".frame_b", indexed_name<"top_end", K>() + ".frame_b">...);
  }(std::make_integer_sequence<int, N + 1>{}, std::make_integer_sequence<int, N>{});
}
/// window_row's scene under a short name of its own (flange::renamed): a
/// row of 40 windows has some 400 components, whose list would otherwise be
/// spelt out in every function its dynamics instantiate.
template <int N, class Params, class Axis>
struct window_row_scene : decltype(window_row_structure<N, Params, Axis>(std::declval<const Params&>())) {};

/// A row of N parallelogram windows, planar about z: N + 1 posts of length
/// h pivot on the ground at x = i·w ("post_pivot<i>", q = the post's angle
/// from the ground line), and N top bars of length w each join two posts,
/// pinned to post i ("top_pin<i>", relative to the post) and to post i + 1
/// ("top_end<i>", written last in its loop and cut). 2N + 1 links, N loops,
/// 2N constraint rows; one degree of freedom: every post turns alike and the
/// top bars stay level. With the posts flat (q = 0 or π) the top bars line
/// up with them: a singular position of every loop at once. The loops share
/// posts, so neighbouring windows' constraints are coupled and the others
/// are not: the constraint solve's structure is banded. With Axis =
/// axis::any every joint turns about p.axis given at run time (at right
/// angles to x; its plane then holds the row): each cut gives a spatial
/// joint's five rows, three of them redundant.
template <int N, class Params = window_row_params, class Axis = axis::z>
System<window_row_scene<N, Params, Axis>> window_row(const Params& p) {
  return flange::detail::named_system<window_row_scene<N, Params, Axis>>(window_row_structure<N, Params, Axis>(p));
}

/// The piston's position x(θ) = r·cos θ + √(l² − r²·sin² θ) and its first and
/// second derivatives in θ: ẋ = x'·θ̇, ẍ = x'·θ̈ + x''·θ̇².
struct slider_kinematics {
  double x, dx, ddx;
};
inline slider_kinematics piston(const slider_crank_params& p, double th) {
  const double r = p.crank, l = p.rod, s = std::sin(th), c = std::cos(th);
  const double w = std::sqrt(l * l - r * r * s * s);
  const double x = r * c + w;
  const double dx = -r * s - r * r * s * c / w;
  const double ddx = -r * c - r * r * (c * c - s * s) / w - std::pow(r * r * s * c, 2) / (w * w * w);
  return {x, dx, ddx};
}

}  // namespace flange::models
