// Contact shapes beyond the sphere (forces/contact_geometry.hpp): a box
// thrown onto the ground against Simbody's HuntCrossleyForce on its corners'
// spheres; a box at rest (its four corners carry m·g), creeping on an incline
// at the regularised friction's speed, sliding to a stop at the closed-form
// distance; a capsule rolling down an incline; a sphere's overlap with a box
// at its faces, edges, corners and inside; a ball reflected by a tilted box;
// a ball hitting a free box (momentum kept); bad shape parameters.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <vector>

#include "simbody/free_body_rows.hpp"

using namespace flange;
namespace cs = contact_scenes;

namespace {
using BoxGround = Contact<"box_ground", contact_shape::box, contact_shape::half_space>;

contact_material material(double dissipation, double mu_s, double mu_d, double mu_v = 0) {
  return {.stiffness = cs::stiffness, .dissipation = dissipation, .static_friction = mu_s, .dynamic_friction = mu_d,
          .viscous_friction = mu_v};
}

const Vec3d box_h(cs::box_h[0], cs::box_h[1], cs::box_h[2]);

/// The box of contact_scenes.hpp on a FreeMotion above the half-space n·p ≤ 0.
template <class Gravity = gravity_kind::uniform>
auto box(const contact_material& m, const Vec3d& n = Vec3d::UnitY(), double vt = cs::transition_velocity) {
  return scene(World<"world", Gravity>{}, FreeMotion<"fly">{},
               Body<"box">({.m = cs::box_m, .J = Vec3d(cs::box_J[0], cs::box_J[1], cs::box_J[2]).asDiagonal()}),
               BoxGround({.a = {.half_extents = box_h, .corner_radius = cs::corner_radius},
                          .b = {.n = n},
                          .material_a = m,
                          .material_b = m,
                          .transition_velocity = vt}),
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "box.frame_a">,
               connect<"fly.frame_b", "box_ground.frame_a">, connect<"world.frame_b", "box_ground.frame_b">);
}
using Box = decltype(box(material(0, 0, 0)));
using X = Box::state_type;

/// A FreeMotion state: position r, the unit quaternion (x, y, z, w) of a
/// turn by `angle` about `axis`, velocity v, ω in body axes.
X start(const Vec3d& r, const Vec3d& v, double angle = 0, const Vec3d& axis = Vec3d::UnitZ(),
        const Vec3d& w = Vec3d::Zero()) {
  X x{};
  for (int i = 0; i < 3; ++i) {
    x[i] = r[i];
    x[3 + i] = std::sin(angle / 2) * axis[i];
    x[7 + i] = v[i];
    x[10 + i] = w[i];
  }
  x[6] = std::cos(angle / 2);
  return x;
}

/// The penetration at which n_c equal corners (same material on both sides,
/// so k = E^(2/3)/2) carry the weight w: w/n_c = (4/3)·k·δ·√(ρ·k·δ).
double rest_depth(double w, int n_c, double radius = cs::corner_radius) {
  const double k = std::cbrt(cs::stiffness * cs::stiffness) / 2;
  return std::pow(3 * w / (4 * n_c * k * std::sqrt(radius * k)), 2.0 / 3.0);
}

/// The box's eight corners' normal forces and penetrations.
template <class Sol>
std::array<double, 8> corner_forces(const Sol& sol) {
  return {sol.template internal<"box_ground", "f_n[0]">(), sol.template internal<"box_ground", "f_n[1]">(),
          sol.template internal<"box_ground", "f_n[2]">(), sol.template internal<"box_ground", "f_n[3]">(),
          sol.template internal<"box_ground", "f_n[4]">(), sol.template internal<"box_ground", "f_n[5]">(),
          sol.template internal<"box_ground", "f_n[6]">(), sol.template internal<"box_ground", "f_n[7]">()};
}
template <class Sol>
std::array<double, 8> corner_depths(const Sol& sol) {
  return {sol.template internal<"box_ground", "δ[0]">(), sol.template internal<"box_ground", "δ[1]">(),
          sol.template internal<"box_ground", "δ[2]">(), sol.template internal<"box_ground", "δ[3]">(),
          sol.template internal<"box_ground", "δ[4]">(), sol.template internal<"box_ground", "δ[5]">(),
          sol.template internal<"box_ground", "δ[6]">(), sol.template internal<"box_ground", "δ[7]">()};
}
}  // namespace

#ifdef FLANGE_SIMBODY_CONTACT
TEST_CASE("a box thrown onto the ground follows Simbody's HuntCrossleyForce on its corners") {
  // contact_reference.cpp wrote the ball's trajectory, then the box's.
  const auto rows = cs::read_block(FLANGE_SIMBODY_CONTACT, 1);
  REQUIRE(rows.size() == cs::samples + 1);
  const auto s = box(material(cs::dissipation, cs::static_friction, cs::dynamic_friction, cs::viscous_friction));
  const Vec3d axis(cs::box_axis[0], cs::box_axis[1], cs::box_axis[2]);
  const X x0 = start({0, cs::box_y0, 0}, {cs::box_v0[0], cs::box_v0[1], cs::box_v0[2]}, cs::box_angle, axis,
                     {cs::box_w0[0], cs::box_w0[1], cs::box_w0[2]});
  for (int i = 0; i < 13; ++i) REQUIRE(std::abs(x0[i] - rows[0][i + 1]) < 1e-15);  // the same start
  X last{};
  const auto c = cs::compare(s, x0, rows, last);
  INFO("largest difference from Simbody " << c.worst << ", residual " << c.worst_residual << ", lowest centre "
                                           << c.lowest);
  CHECK(c.worst < 1e-6);
  CHECK(c.worst_residual < 1e-12);
  CHECK(c.lowest < box_h.minCoeff());  // it did land
  // It ends on a face: four corners touching.
  const auto end = recover(s, rows.back()[0], last);
  int touching = 0;
  for (double d : corner_depths(end)) touching += d > 0;
  CHECK(touching == 4);
}
#endif

TEST_CASE("a box at rest on the ground: its four lower corners carry its weight") {
  // Dropped flat from 5 mm onto the ground with the contact's dissipation,
  // then left for 10 s: the vertical and rocking oscillations decay (by
  // about e^−37), and the weight is carried by the four lower corners, each
  // a quarter by symmetry, at the penetration Hertz's law gives. Integrated
  // with rosenbrock4, which settles onto the rest state (dopri5, at the edge
  // of its stability on the stiff contact, keeps a jitter of about its
  // tolerance there).
  const auto s = box(material(cs::dissipation, 0.8, 0.8));
  const double w = cs::box_m * cs::g;
  const X x = simulate<method::rosenbrock4>(s, start({0, box_h.y() + 0.005, 0}, Vec3d::Zero()), 0.0, 10.0,
                                            {.tolerance = 1e-10});
  const auto sol = recover(s, 10.0, x);
  const auto f = corner_forces(sol);
  const auto d = corner_depths(sol);
  double sum = 0;
  for (double fi : f) sum += fi;
  INFO("sum of the normal forces " << sum << " N against m·g = " << w << "; corner depths " << d[0] << " "
                                   << d[2] << " " << d[4] << " " << d[6] << ", Hertz's " << rest_depth(w, 4));
  CHECK(std::abs(sum - w) < 1e-9 * w);
  for (int i = 0; i < 8; ++i) {
    if (i & 2) {  // an upper corner (+y)
      CHECK(f[i] == 0);
    } else {
      CHECK(std::abs(f[i] - w / 4) < 1e-9 * w);
      CHECK(std::abs(d[i] - rest_depth(w, 4)) < 1e-9 * rest_depth(w, 4));
    }
  }
  CHECK(std::abs(x[0]) + std::abs(x[2]) < 1e-12);  // nothing pushes it sideways
}

TEST_CASE("a box on an incline creeps at the regularised friction's speed, v_t·tan θ/μ") {
  // With μ_s = μ_d = μ and no viscous friction the friction below v_t is
  // μ·f_n·v_s/v_t: holding the box on a slope of angle θ takes
  // f_t = tan θ·f_n, so it creeps down at v_s = v_t·tan θ/μ, exactly, once
  // the start's transient has died. (The stated bound on a resting box's
  // creep: this speed times the time.)
  const double theta = 10 * std::numbers::pi / 180, mu = 0.8, vt = 1e-3;
  const Vec3d n(-std::sin(theta), std::cos(theta), 0);  // the slope rises along +x
  const auto s = box(material(cs::dissipation, mu, mu), n, vt);
  // Resting on its face, turned with the slope, at Hertz's penetration for cos θ of its weight.
  const double depth = rest_depth(cs::box_m * cs::g * std::cos(theta), 4);
  const X x0 = start((box_h.y() - depth) * n, Vec3d::Zero(), theta, Vec3d::UnitZ());
  const Vec3d down(-std::cos(theta), -std::sin(theta), 0);
  auto along = [&](const X& x) { return Vec3d(x[0], x[1], x[2]).dot(down); };
  const X x5 = simulate(s, x0, 0.0, 5.0, {.tolerance = 1e-10});
  const X x10 = simulate(s, x5, 5.0, 10.0, {.tolerance = 1e-10});
  const double creep = (along(x10) - along(x5)) / 5, expected = vt * std::tan(theta) / mu;
  INFO("creeps at " << creep << " m/s against v_t·tan θ/μ = " << expected << "; in 10 s " << along(x10) << " m");
  CHECK(std::abs(creep - expected) < 1e-6 * expected);
  CHECK(along(x10) < 10 * expected * 1.01);  // the bound over 10 s, with the start's transient
}

TEST_CASE("a box sliding at v0 stops after (v0² + v_t²)/(2·μ·g), without tipping") {
  // Above v_t the friction is μ·m·g, so it slides (v0² − v_t²)/(2·μ·g) to
  // reach v_t; below, μ·m·g·v/v_t slows it exponentially over v_t²/(μ·g)
  // more: (v0² + v_t²)/(2·μ·g) in all, the rigid-body v0²/(2·μ·g) plus
  // the regularisation's v_t²/(2·μ·g). The compliant contact adds a
  // bound of its own: the friction at the ground pitches the box forward by
  // θ_s (the front corners sink), and starting and stopping each set it
  // rocking with energy ½·(μ·m·g·h_y/θ_s)·θ_s², which the normal force's
  // damping takes instead of the friction: the box slides short by at most
  // h_y·θ_s.
  const double mu = 0.5, vt = 1e-3, v0 = 1.0;
  const auto s = box(material(cs::dissipation, mu, mu), Vec3d::UnitY(), vt);
  const double depth = rest_depth(cs::box_m * cs::g, 4);
  const X x0 = start({0, box_h.y() - depth, 0}, {v0, 0, 0});
  std::vector<double> times;
  for (int k = 0; k <= 300; ++k) times.push_back(0.01 * k);
  const auto tr = simulate(s, x0, times, {.tolerance = 1e-10});
  double tilt = 0;
  for (const auto& x : tr.x) tilt = std::max(tilt, 2 * std::asin(std::min(1.0, Vec3d(x[3], x[4], x[5]).norm())));
  const double distance = tr.x.back()[0], expected = (v0 * v0 + vt * vt) / (2 * mu * cs::g);
  INFO("slid " << distance << " m against (v0² + v_t²)/(2·μ·g) = " << expected << ", short by "
               << expected - distance << " against h_y·θ_s = " << box_h.y() * tilt << "; largest tilt " << tilt
               << " rad; final speed " << tr.x.back()[7]);
  CHECK(distance <= expected);
  CHECK(expected - distance < box_h.y() * tilt);
  CHECK(tilt < 1e-3);  // it does not tip
  CHECK(std::abs(tr.x.back()[7]) < 1e-6);  // at rest
}

TEST_CASE("a capsule lying across an incline rolls down it at g·sin θ/(1 + J/(m·r²))") {
  // Both ends' spheres touch; with μ large enough it rolls without slipping
  // (up to the regularised friction's creep), about its axis (z), down a
  // slope rising along +x. J is the capsule body's inertia about its axis;
  // r the radius it rolls on: the contact point lies in the middle of the
  // overlap δ, so r = radius − δ/2.
  const double theta = 15 * std::numbers::pi / 180, r = 0.05, m = 1.5, J = 0.5 * m * r * r, vt = 1e-3;
  const Vec3d n(-std::sin(theta), std::cos(theta), 0);
  const auto mat = material(cs::dissipation, 0.9, 0.9);
  const auto s = scene(
      World<"world">{}, FreeMotion<"fly">{}, Body<"rod">({.m = m, .J = Vec3d(0.02, 0.02, J).asDiagonal()}),
      Contact<"rod_ground", contact_shape::capsule, contact_shape::half_space>(
          {.a = {.radius = r, .half_length = 0.2}, .b = {.n = n}, .material_a = mat, .material_b = mat,
           .transition_velocity = vt}),
      connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "rod.frame_a">,
      connect<"fly.frame_b", "rod_ground.frame_a">, connect<"world.frame_b", "rod_ground.frame_b">);
  using Y = decltype(s)::state_type;
  Y x{};
  const double depth = rest_depth(m * cs::g * std::cos(theta), 2, r);
  for (int i = 0; i < 3; ++i) x[i] = (r - depth) * n[i];
  x[6] = 1;
  const Vec3d down(-std::cos(theta), -std::sin(theta), 0);
  auto speed = [&](const Y& y) { return Vec3d(y[7], y[8], y[9]).dot(down); };
  const Y x1 = simulate(s, x, 0.0, 0.5, {.tolerance = 1e-10});
  const Y x2 = simulate(s, x1, 0.5, 1.0, {.tolerance = 1e-10});
  const double rc = r - depth / 2;
  const double a = (speed(x2) - speed(x1)) / 0.5, expected = cs::g * std::sin(theta) / (1 + J / (m * rc * rc));
  const auto sol = recover(s, 1.0, x2);
  const double f0 = sol.internal<"rod_ground", "f_n[0]">(), f1 = sol.internal<"rod_ground", "f_n[1]">();
  const double slip = sol.internal<"rod_ground", "v_s[0]">();
  INFO("rolls at " << a << " m/s² against " << expected << " (relative " << std::abs(a - expected) / expected << ")" << "; end forces " << f0 << ", " << f1 << " N; slip "
                   << slip << " m/s");
  // The steady creep (slip ≈ v_t·(the friction it needs)/(μ·f_n)) does not change a.
  CHECK(std::abs(a - expected) < 1e-8 * expected);
  CHECK(std::abs(f0 - f1) < 1e-6 * f0);  // both ends carry half
  CHECK(std::abs(f0 + f1 - m * cs::g * std::cos(theta)) < 1e-6 * m * cs::g);
  CHECK(slip < vt);
}

TEST_CASE("a sphere's overlap with a box: at a face, an edge, a corner, and from inside") {
  // The box: half extents (1, 0.5, 0.25), edges rounded by ρ = 0.05, at the
  // origin of frame b; a sphere of radius 0.1 at frame a.
  const detail::contact_pair<contact_shape::sphere, contact_shape::box> g{
      {.radius = 0.1}, {.half_extents = {1, 0.5, 0.25}, .corner_radius = 0.05}};
  frame_kinematics<double> b;
  b.r.setZero();
  b.R.setIdentity();
  b.v.setZero();
  b.w.setZero();
  b.a.setZero();
  b.wd.setZero();
  auto at = [&](const Vec3d& c) {
    frame_kinematics<double> a = b;
    a.r = c;
    return g.overlap(0, a, b);
  };
  // Over the top face, 1 cm deep.
  auto o = at({0.3, 0.59, 0});
  CHECK(std::abs(o.depth - 0.01) < 1e-15);
  CHECK((o.N - Vec3d::UnitY()).norm() < 1e-15);
  CHECK((o.surface - Vec3d(0.3, 0.5, 0)).norm() < 1e-15);
  // Off the corner (+, +, +) along the diagonal: the rounding's sphere about
  // the inner corner (0.95, 0.45, 0.2).
  const Vec3d u = Vec3d::Ones().normalized(), inner(0.95, 0.45, 0.2);
  o = at(inner + (0.05 + 0.1 - 0.01) * u);
  CHECK(std::abs(o.depth - 0.01) < 1e-15);
  CHECK((o.N - u).norm() < 1e-15);
  CHECK((o.surface - (inner + 0.05 * u)).norm() < 1e-15);
  // Off the edge along z at (+x, +y): the normal in the x-y plane.
  const Vec3d e = Vec3d(1, 1, 0).normalized();
  o = at(Vec3d(0.95, 0.45, 0.1) + 0.2 * e);
  CHECK(std::abs(o.depth - (0.15 - 0.2)) < 1e-15);  // apart by 5 cm
  CHECK((o.N - e).norm() < 1e-15);
  // The centre inside, nearest the +x face: out through it.
  o = at({0.9, 0, 0});
  CHECK(std::abs(o.depth - 0.2) < 1e-15);
  CHECK((o.N - Vec3d::UnitX()).norm() < 1e-15);
  CHECK((o.surface - Vec3d(1, 0, 0)).norm() < 1e-15);
  // The box turned and moved: the same overlap in world coordinates.
  const Mat3d Rb = Eigen::AngleAxisd(0.7, Vec3d(1, 2, 3).normalized()).toRotationMatrix();  // frame b into world
  b.R = Rb.transpose();
  b.r = Vec3d(0.2, -0.4, 1.0);
  o = at(b.r + Rb * Vec3d(0.3, 0.59, 0));
  CHECK(std::abs(o.depth - 0.01) < 1e-14);
  CHECK((o.N - Rb * Vec3d::UnitY()).norm() < 1e-14);
}

TEST_CASE("a ball thrown at a tilted box's face comes back mirrored, without dissipation or friction") {
  // No gravity. The force is along the face's normal N throughout the
  // impact, and none is lost: the velocity leaves as v − 2·(v·N)·N, the spin
  // stays zero. The box (a table, fixed to the World) is turned by 30° about z
  // by its axes, and moved by its centre.
  const double c = 0.5;
  const Mat3d axes = Eigen::AngleAxisd(-c, Vec3d::UnitZ()).toRotationMatrix().transpose() *
                     Eigen::AngleAxisd(0, Vec3d::UnitX()).toRotationMatrix();
  const Vec3d N = axes.row(1).transpose();  // the top face's normal, frame (= world) coordinates
  const auto mat = material(0, 0, 0);
  const auto s = scene(World<"world", gravity_kind::none>{}, FreeMotion<"fly">{},
                       Body<"ball">({.m = 1.0, .J = Mat3d::Identity() * 0.004}),
                       Contact<"hit", contact_shape::sphere, contact_shape::box>(
                           {.a = {.radius = 0.1},
                            .b = {.half_extents = {1, 0.25, 1}, .center = -0.25 * N, .axes = axes, .corner_radius = 0.01},
                            .material_a = mat,
                            .material_b = mat}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "ball.frame_a">,
                       connect<"fly.frame_b", "hit.frame_a">, connect<"world.frame_b", "hit.frame_b">);
  using Y = decltype(s)::state_type;
  // Aimed at the face's point at the origin, 0.3 m away, at 1 m/s.
  const Vec3d v_in = Vec3d(0.6, -1, 0.3).normalized();
  Y x{};
  for (int i = 0; i < 3; ++i) {
    x[i] = (-0.3 * v_in + 0.1 / -v_in.dot(N) * -v_in)[i];
    x[7 + i] = v_in[i];
  }
  x[6] = 1;
  const double E0 = recover(s, 0.0, x).energy();
  x = simulate(s, x, 0.0, 1.0, {.tolerance = 1e-12});
  const Vec3d v_out(x[7], x[8], x[9]), mirrored = v_in - 2 * v_in.dot(N) * N;
  const auto end = recover(s, 1.0, x);
  INFO("leaves at " << v_out.transpose() << " against " << mirrored.transpose() << "; spin "
                    << Vec3d(x[10], x[11], x[12]).norm());
  CHECK((v_out - mirrored).norm() < 1e-9);
  CHECK(Vec3d(x[10], x[11], x[12]).norm() < 1e-12);
  CHECK(std::abs(end.energy() - E0) < 1e-10 * E0);
  const double depth = end.internal<"hit", "δ">();
  CHECK(depth == 0);  // apart again
}

TEST_CASE("a ball hits a free box: momentum kept, energy kept without dissipation") {
  // No gravity. The ball strikes the box's face off its centre, setting it
  // spinning; friction and dissipation on or off.
  for (double c : {0.0, 0.5}) {
    const auto mat = material(c, c > 0 ? 0.6 : 0, c > 0 ? 0.4 : 0);
    const Mat3d Jb = Vec3d(cs::box_J[0], cs::box_J[1], cs::box_J[2]).asDiagonal();
    const auto s = scene(World<"world", gravity_kind::none>{}, FreeMotion<"fa">{},
                         Body<"ball">({.m = 0.5, .J = Mat3d::Identity() * 0.002}), FreeMotion<"fb">{},
                         Body<"box">({.m = cs::box_m, .J = Jb}),
                         Contact<"hit", contact_shape::sphere, contact_shape::box>(
                             {.a = {.radius = 0.1},
                              .b = {.half_extents = box_h, .corner_radius = cs::corner_radius},
                              .material_a = mat,
                              .material_b = mat}),
                         connect<"world.frame_b", "fa.frame_a">, connect<"fa.frame_b", "ball.frame_a">,
                         connect<"world.frame_b", "fb.frame_a">, connect<"fb.frame_b", "box.frame_a">,
                         connect<"fa.frame_b", "hit.frame_a">, connect<"fb.frame_b", "hit.frame_b">);
    using Y = decltype(s)::state_type;
    Y x{};
    // The state: q of fa (r, quaternion) and fb, then v of fa (v, ω) and fb.
    x[0] = -0.5;  // the ball, level with the box's upper half, moving along +x with some spin
    x[1] = 0.05;
    x[6] = 1;
    x[13] = 1;  // the box at the origin
    x[14] = 2.0;
    x[19] = 3.0;
    const auto p0 = momentum(s, x);
    const double E0 = recover(s, 0.0, x).energy();
    x = simulate(s, x, 0.0, 0.5, {.tolerance = 1e-12});
    const auto p1 = momentum(s, x);
    const double E1 = recover(s, 0.5, x).energy();
    INFO("c = " << c << ": box velocity " << x[20] << " " << x[21] << ", spin " << x[25] << "; energy " << E0
                << " → " << E1);
    CHECK((p1.linear - p0.linear).norm() < 1e-10);
    CHECK((p1.angular - p0.angular).norm() < 1e-10);
    CHECK(x[20] > 0.1);  // it was hit
    if (c == 0) {
      CHECK(std::abs(E1 - E0) < 1e-9 * E0);
    } else {
      CHECK(E1 < E0);
    }
  }
}

TEST_CASE("box and capsule parameters are checked at construction") {
  const auto m = material(0, 0, 0);
  using Capsule = Contact<"rod_ground", contact_shape::capsule, contact_shape::half_space>;
  using OnBox = Contact<"on_box", contact_shape::sphere, contact_shape::box>;
  CHECK_THROWS_WITH(BoxGround({.a = {.half_extents = {0.5, 0, 0.5}}, .material_a = m, .material_b = m}),
                    Catch::Contains("Contact \"box_ground\": a.half_extents = [0.5 0 0.5] must be positive"));
  CHECK_THROWS_WITH(BoxGround({.a = {.half_extents = {0.5, 0.25, 0.5}, .corner_radius = 0.375}, .material_a = m,
                               .material_b = m}),
                    Catch::Contains("a.corner_radius = 0.375 exceeds the smallest half extent 0.25"));
  CHECK_THROWS_WITH(BoxGround({.a = {.half_extents = {0.1, 0.1, 0.1}, .corner_radius = 0}, .material_a = m,
                               .material_b = m}),
                    Catch::Contains("a.corner_radius = 0 must be positive"));
  CHECK_THROWS_WITH(OnBox({.a = {.radius = 0.1}, .b = {.half_extents = {1, 1, 1}, .axes = Mat3d::Identity() * 2},
                           .material_a = m, .material_b = m}),
                    Catch::Contains("Contact \"on_box\": b.axes"));
  CHECK_THROWS_WITH(Capsule({.a = {.radius = 0, .half_length = 0.2}, .material_a = m, .material_b = m}),
                    Catch::Contains("Contact \"rod_ground\": a.radius = 0 must be positive"));
  CHECK_THROWS_WITH(Capsule({.a = {.radius = 0.1, .half_length = -1}, .material_a = m, .material_b = m}),
                    Catch::Contains("a.half_length = -1 is negative"));
  CHECK_THROWS_WITH(Capsule({.a = {.radius = 0.1, .half_length = 0.2, .axis = {1, 1, 0}}, .material_a = m,
                             .material_b = m}),
                    Catch::Contains("a.axis = [1 1 0] is not a unit vector"));
  CHECK_THROWS_WITH(Capsule({.a = {.radius = 0.1, .half_length = std::nan("")}, .material_a = m, .material_b = m}),
                    Catch::Contains("a.half_length is not finite"));
}

TEST_CASE("a scene that starts deep in the ground, or a contact too soft for its load, stops with the pair's name") {
  const auto s = box(material(cs::dissipation, 0.5, 0.5));
  // Started with its centre 0.04 m above the ground: 0.06 m deep, more than
  // half its smallest half extent (0.1 m).
  try {
    (void)simulate(s, start({0, 0.04, 0}, Vec3d::Zero()), 0.0, 0.1);
    FAIL("no error");
  } catch (const simulation_error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("Contact \"box_ground\": its shapes overlap by 0.06") != std::string::npos);
    CHECK(std::string(e.what()).find(" m at the start") != std::string::npos);
    CHECK(std::string(e.what()).find("more than half the smaller shape's size (0.1 m)") != std::string::npos);
    CHECK(e.time == 0);
  }
  // A soft contact (E = 1e3 Pa: Hertz's k = 50) under a falling box sinks
  // through: stopped once it is a half extent deep.
  contact_material soft = material(cs::dissipation, 0.5, 0.5);
  soft.stiffness = 1e3;
  const auto sunk = box(soft);
  try {
    (void)simulate(sunk, start({0, box_h.y() + 0.01, 0}, Vec3d::Zero()), 0.0, 2.0);
    FAIL("no error");
  } catch (const simulation_error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("Contact \"box_ground\": its shapes overlap by") != std::string::npos);
    CHECK(std::string(e.what()).find("more than the smaller shape's size (0.1 m): the contact is too soft") !=
          std::string::npos);
    CHECK(e.time > 0);
    CHECK(e.state.size() == 13);
  }
}

TEST_CASE("a BodyBox and a BodyCylinder lend their shapes to a Contact in one line") {
  // A BodyBox 0.4 m along (1, 0, 1)/√2 from frame_a, 0.1 wide along y, 0.05 high.
  const Vec3d r = 0.4 * Vec3d(1, 0, 1).normalized();
  const BodyBox<"crate"> crate({.r = r, .width = 0.1, .height = 0.05});
  const auto b = contact_shape::box_of(crate, 0.005);
  CHECK((b.half_extents - Vec3d(0.2, 0.05, 0.025)).norm() < 1e-15);
  CHECK((b.center - r / 2).norm() < 1e-15);
  CHECK((b.axes.row(0).transpose() - r.normalized()).norm() < 1e-15);
  CHECK((b.axes * b.axes.transpose() - Mat3d::Identity()).norm() < 1e-15);
  CHECK(b.corner_radius == 0.005);
  CHECK(contact_shape::box_of(crate, 1.0).corner_radius == 0.025);  // at most the smallest half extent
  // Its box's corners: frame_a's origin and r are the centres of two opposite faces.
  const detail::contact_pair<contact_shape::box, contact_shape::half_space> pair{b, {}};
  for (int i = 0; i < 8; ++i) {
    const double along = pair.center(i).dot(r.normalized());
    CHECK(std::abs(std::abs(along - 0.2) - (0.2 - 0.005)) < 1e-15);
  }
  // A BodyCylinder 0.5 m long along x, 0.1 across: the capsule of its radius and length.
  const BodyCylinder<"roller"> roller({.r = {0.5, 0, 0}, .diameter = 0.1});
  const auto c = contact_shape::capsule_of(roller);
  CHECK(c.radius == 0.05);
  CHECK(std::abs(c.half_length - 0.2) < 1e-15);
  CHECK((c.center - Vec3d(0.25, 0, 0)).norm() < 1e-15);
  CHECK((c.axis - Vec3d::UnitX()).norm() < 1e-15);
}
