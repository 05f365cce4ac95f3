// Andrews' squeezing mechanism: seven bodies in a plane, three loops that
// meet at one point E, a spring and a motor; a standard test problem for
// index-3 DAE solvers, with published reference values (Hairer & Wanner,
// "Solving Ordinary Differential Equations II", sec. VII.7; Mazzia & Magherini,
// "Test Set for IVP Solvers", problem "andrews", whose reference solution at
// t = 0.03 was computed with PSIDE at tolerance 1e-14).
//
// The test set writes it in seven relative angles β, Θ, γ, Φ, δ, Ω, ε and
// six position constraints; here it is written as components. Body 1 turns
// by β about the origin O and carries body 2 at rr from O (Θ relative); body
// 3 turns by γ about B, body 5 by δ and body 7 by ε about A; body 4 hangs on
// body 5 at zt from A (Φ relative), body 6 on body 7 at u from A (Ω
// relative). Bodies 3, 4 and 6 meet body 2's end E in three revolutes (the
// loops' joints); a spring of stiffness c0 and length l0 joins D on body 3
// to the fixed point C; a motor turns body 1 with torque mom. No gravity.
// Each body's centre of mass is where the test set's mass matrix puts it:
// along the line to E for bodies 2, 4 and 6; at the distance it gives
// from the fixed pivot for bodies 1, 3, 5 and 7 (any direction: they only
// turn about that pivot).
#pragma once
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <initializer_list>
#include <tuple>

#include <flange/flange.hpp>

#include "scene_orders.hpp"

namespace flange::test {

struct andrews_params {
  double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706, m7 = .05498;
  double xa = -.06934, ya = -.00227, xb = -0.03635, yb = .03273, xc = .014, yc = .072, c0 = 4530;
  double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5, i6 = 5.667e-7, i7 = 1.912e-5;
  double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5, l0 = 7785e-5;
  double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2, ta = 2308e-5, tb = 916e-5;
  double u = 4e-2, ua = 1228e-5, ub = 449e-5, zf = 2e-2, zt = 4e-2, fa = 1421e-5, mom = 33e-3;
};

/// The test set's initial angles (at rest) and its reference solution at
/// t = 0.03: angles and rates (y1…y14), in the test set's order β, Θ, γ, Φ, δ, Ω, ε
/// (the joints beta, theta, gamma, phi, delta, omega, epsilon).
inline constexpr std::array<double, 7> andrews_q0{-0.0617138900142764496358948458001, 0,
                                                  0.455279819163070380255912382449,  0.222668390165885884674473185609,
                                                  0.487364979543842550225598953530,  -0.222668390165885884674473185609,
                                                  1.23054744454982119249735015568};
inline constexpr std::array<double, 7> andrews_q_ref{0.1581077119629904e+2,  -0.1575637105984298e+2, 0.4082224013073101e-1,
                                                     -0.5347301163226948e+0, 0.5244099658805304e+0,  0.5347301163226948e+0,
                                                     0.1048080741042263e+1};
inline constexpr std::array<double, 7> andrews_v_ref{0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
                                                     0.1929337464421385e+2, 0.5735699284790808e+0,  -0.1929337464421385e+2,
                                                     0.3231791658026955e+0};

/// The mechanism's components and connections, in the order written here:
/// the loops' three joints at E last among the components (so they are cut).
inline auto andrews_parts(const andrews_params& p) {
  auto J = [](double i) { return Mat3d(Vec3d(i, i, i).asDiagonal()); };
  return std::make_tuple(
      World<"world">({.g = Vec3d::Zero()}),
      revolute<"beta", axis::z>([mom = p.mom](auto t) { return mom + 0.0 * t; }),
      Body<"b1", cm::offset>({.m = p.m1, .J = J(p.i1), .r_cm = {p.ra, 0, 0}}),
      FixedTranslation<"b1_p">({.d = {p.rr, 0, 0}}), Revolute<"theta", axis::z>{},
      Body<"b2", cm::offset>({.m = p.m2, .J = J(p.i2), .r_cm = {-p.da, 0, 0}}),
      FixedTranslation<"b2_e">({.d = {-p.d, 0, 0}}),
      FixedTranslation<"to_b">({.d = {p.xb, p.yb, 0}}), Revolute<"gamma", axis::z>{},
      Body<"b3", cm::offset>({.m = p.m3, .J = J(p.i3), .r_cm = {p.sa, p.sb, 0}}),
      FixedTranslation<"b3_e">({.d = {0, -p.ss, 0}}), FixedTranslation<"b3_d">({.d = {p.sd, -p.sc, 0}}),
      FixedTranslation<"to_a">({.d = {p.xa, p.ya, 0}}), Revolute<"delta", axis::z>{},
      Body<"b5", cm::offset>({.m = p.m5, .J = J(p.i5), .r_cm = {p.ta, p.tb, 0}}),
      FixedTranslation<"b5_z">({.d = {p.zt, 0, 0}}), Revolute<"phi", axis::z>{},
      Body<"b4", cm::offset>({.m = p.m4, .J = J(p.i4), .r_cm = {0, -(p.e - p.ea), 0}}),
      FixedTranslation<"b4_e">({.d = {0, -p.e, 0}}), Revolute<"epsilon", axis::z>{},
      Body<"b7", cm::offset>({.m = p.m7, .J = J(p.i7), .r_cm = {p.ua, p.ub, 0}}),
      FixedTranslation<"b7_u">({.d = {0, -p.u, 0}}), Revolute<"omega", axis::z>{},
      Body<"b6", cm::offset>({.m = p.m6, .J = J(p.i6), .r_cm = {p.zf - p.fa, 0, 0}}),
      FixedTranslation<"b6_e">({.d = {p.zf, 0, 0}}), FixedTranslation<"to_c">({.d = {p.xc, p.yc, 0}}),
      Spring<"spring">({.c = p.c0, .s0 = p.l0}), Revolute<"e3", axis::z>{}, Revolute<"e4", axis::z>{},
      Revolute<"e6", axis::z>{},
      // O: body 1 and its chain to E
      connect<"world.frame_b", "beta.frame_a">, connect<"beta.frame_b", "b1.frame_a">,
      connect<"b1.frame_a", "b1_p.frame_a">, connect<"b1_p.frame_b", "theta.frame_a">,
      connect<"theta.frame_b", "b2.frame_a">, connect<"b2.frame_a", "b2_e.frame_a">,
      // B: body 3, its point E and the spring's end D
      connect<"world.frame_b", "to_b.frame_a">, connect<"to_b.frame_b", "gamma.frame_a">,
      connect<"gamma.frame_b", "b3.frame_a">, connect<"b3.frame_a", "b3_e.frame_a">,
      connect<"b3.frame_a", "b3_d.frame_a">,
      // A: bodies 5 and 4, bodies 7 and 6
      connect<"world.frame_b", "to_a.frame_a">, connect<"to_a.frame_b", "delta.frame_a">,
      connect<"delta.frame_b", "b5.frame_a">, connect<"b5.frame_a", "b5_z.frame_a">,
      connect<"b5_z.frame_b", "phi.frame_a">, connect<"phi.frame_b", "b4.frame_a">,
      connect<"b4.frame_a", "b4_e.frame_a">, connect<"to_a.frame_b", "epsilon.frame_a">,
      connect<"epsilon.frame_b", "b7.frame_a">, connect<"b7.frame_a", "b7_u.frame_a">,
      connect<"b7_u.frame_b", "omega.frame_a">, connect<"omega.frame_b", "b6.frame_a">,
      connect<"b6.frame_a", "b6_e.frame_a">,
      // the spring from D to C
      connect<"world.frame_b", "to_c.frame_a">, connect<"b3_d.frame_b", "spring.frame_a">,
      connect<"to_c.frame_b", "spring.frame_b">,
      // the three loops meet at E
      connect<"b2_e.frame_b", "e3.frame_a">, connect<"e3.frame_b", "b3_e.frame_b">,
      connect<"b2_e.frame_b", "e4.frame_a">, connect<"e4.frame_b", "b4_e.frame_b">,
      connect<"b2_e.frame_b", "e6.frame_a">, connect<"e6.frame_b", "b6_e.frame_b">);
}

/// The scene of andrews_parts in its order, or shuffled by Seed
/// (scene_orders.hpp): another writing order, so other joints cut and
/// another tree.
inline auto andrews(const andrews_params& p) { return scene_of(andrews_parts(p)); }
template <unsigned Seed>
auto andrews_shuffled(const andrews_params& p) {
  return shuffled_scene<Seed>(andrews_parts(p));
}

/// The test set's initial state: its seven angles (which close the loops), at rest.
template <class S>
typename S::state_type andrews_initial(const S& s) {
  const auto& q = andrews_q0;
  auto x = initial_state<"beta", "theta", "gamma", "phi", "delta", "omega", "epsilon">(
      s, {.q = q[0]}, {.q = q[1]}, {.q = q[2]}, {.q = q[3]}, {.q = q[4]}, {.q = q[5]}, {.q = q[6]});
  return x;
}

/// The test set's own equations (its andrews.f, the same model written by
/// hand in its seven angles), a second formulation: q̈ from M(q)·q̈ = f(q, q̇)
/// − Gᵀ·λ and G·q̈ = −Ġ·q̇, solved as one dense system.
inline Eigen::Matrix<double, 7, 1> andrews_reference_accelerations(const andrews_params& p, const std::array<double, 7>& y,
                                                                   const std::array<double, 7>& yd) {
  using std::cos;
  using std::sin;
  // The angles the mass matrix and forces depend on (β, δ and ε enter
  // through the constraints only), and the rates the forces do.
  const double th = y[1], ga = y[2], ph = y[3], om = y[5];
  const double bep = yd[0], thp = yd[1], php = yd[3], dep = yd[4], omp = yd[5], epp = yd[6];
  Eigen::Matrix<double, 7, 7> M = Eigen::Matrix<double, 7, 7>::Zero();
  const double eea = p.e - p.ea, zfa = p.zf - p.fa;
  M(0, 0) = p.m1 * p.ra * p.ra + p.m2 * (p.rr * p.rr - 2 * p.da * p.rr * cos(th) + p.da * p.da) + p.i1 + p.i2;
  M(1, 0) = M(0, 1) = p.m2 * (p.da * p.da - p.da * p.rr * cos(th)) + p.i2;
  M(1, 1) = p.m2 * p.da * p.da + p.i2;
  M(2, 2) = p.m3 * (p.sa * p.sa + p.sb * p.sb) + p.i3;
  M(3, 3) = p.m4 * eea * eea + p.i4;
  M(4, 3) = M(3, 4) = p.m4 * (eea * eea + p.zt * eea * sin(ph)) + p.i4;
  M(4, 4) = p.m4 * (p.zt * p.zt + 2 * p.zt * eea * sin(ph) + eea * eea) + p.m5 * (p.ta * p.ta + p.tb * p.tb) + p.i4 + p.i5;
  M(5, 5) = p.m6 * zfa * zfa + p.i6;
  M(6, 5) = M(5, 6) = p.m6 * (zfa * zfa - p.u * zfa * sin(om)) + p.i6;
  M(6, 6) = p.m6 * (zfa * zfa - 2 * p.u * zfa * sin(om) + p.u * p.u) + p.m7 * (p.ua * p.ua + p.ub * p.ub) + p.i6 + p.i7;
  const double xd = p.sd * cos(ga) + p.sc * sin(ga) + p.xb, yd_ = p.sd * sin(ga) - p.sc * cos(ga) + p.yb;
  const double L = std::hypot(xd - p.xc, yd_ - p.yc), force = -p.c0 * (L - p.l0) / L;
  const double fx = force * (xd - p.xc), fy = force * (yd_ - p.yc);
  Eigen::Matrix<double, 7, 1> f;
  f << p.mom - p.m2 * p.da * p.rr * thp * (thp + 2 * bep) * sin(th), p.m2 * p.da * p.rr * bep * bep * sin(th),
      fx * (p.sc * cos(ga) - p.sd * sin(ga)) + fy * (p.sd * cos(ga) + p.sc * sin(ga)),
      p.m4 * p.zt * eea * dep * dep * cos(ph), -p.m4 * p.zt * eea * php * (php + 2 * dep) * cos(ph),
      -p.m6 * p.u * zfa * epp * epp * cos(om), p.m6 * p.u * zfa * omp * (omp + 2 * epp) * cos(om);
  // Each constraint is a sum of a·cos θ + b·sin θ terms, θ a sum of angles:
  // its G row is their derivatives, its bias (Ġ·q̇) their −(a·cos θ + b·sin θ)·θ̇².
  Eigen::Matrix<double, 6, 7> G = Eigen::Matrix<double, 6, 7>::Zero();
  Eigen::Matrix<double, 6, 1> bias = Eigen::Matrix<double, 6, 1>::Zero();
  auto add = [&](int row, double a, double b, std::initializer_list<int> idx) {  // a·cos(Σq) + b·sin(Σq)
    double t = 0, td = 0;
    for (int i : idx) {
      t += y[i];
      td += yd[i];
    }
    const double dv = -a * sin(t) + b * cos(t);
    for (int i : idx) G(row, i) += dv;
    bias[row] += -(a * cos(t) + b * sin(t)) * td * td;
  };
  // x and y of E by the chain O–1–2, less by each other chain.
  for (int k = 0; k < 3; ++k) {
    add(2 * k, p.rr, 0, {0});
    add(2 * k, -p.d, 0, {0, 1});
    add(2 * k + 1, 0, p.rr, {0});
    add(2 * k + 1, 0, -p.d, {0, 1});
  }
  add(0, 0, -p.ss, {2});  // E on body 3
  add(1, p.ss, 0, {2});
  add(2, 0, -p.e, {3, 4});  // E on body 4, on body 5
  add(2, -p.zt, 0, {4});
  add(3, p.e, 0, {3, 4});
  add(3, 0, -p.zt, {4});
  add(4, -p.zf, 0, {5, 6});  // E on body 6, on body 7
  add(4, 0, -p.u, {6});
  add(5, 0, -p.zf, {5, 6});
  add(5, p.u, 0, {6});
  Eigen::Matrix<double, 13, 13> K = Eigen::Matrix<double, 13, 13>::Zero();
  K.topLeftCorner<7, 7>() = M;
  K.topRightCorner<7, 6>() = G.transpose();
  K.bottomLeftCorner<6, 7>() = G;
  Eigen::Matrix<double, 13, 1> r;
  r << f, -bias;
  return K.fullPivLu().solve(r).head<7>();
}

}  // namespace flange::test
