// Hard cases that must stay numerically stable, each against something
// independent: an exact formula, a conservation law, the closed form, or a
// long-double solve. (Labelled "hard" in ctest.)
#include <boost/math/special_functions/ellint_1.hpp>
#include <catch2/catch.hpp>
#include <flange/flange.hpp>

#include "consistency.hpp"
#include "random_params.hpp"

using namespace flange;

namespace {
const models::robot_arm_params P{.m = 1.0, .d = 0.5, .Jx = 0.01, .Jz = 0.02, .g = 9.81};
constexpr double pi = 3.14159265358979323846;
using A = std::array<double, 2>;

/// The first time after t0 at which φ̇ changes sign from `from_sign`, found by
/// bisection on dopri5's dense output (its interpolant is accurate to the tolerance).
template <class S, class Stepper>
double next_turn(const S& s, Stepper& st, double from_sign) {
  while (true) {
    const auto [t0, t1] = st.do_step(s);
    if (from_sign * st.current_state()[1] <= 0) {
      double a = t0, b = t1;
      A x;
      for (int i = 0; i < 80; ++i) {
        const double m = 0.5 * (a + b);
        st.calc_state(m, x);
        (from_sign * x[1] > 0 ? a : b) = m;
      }
      return 0.5 * (a + b);
    }
  }
}
}  // namespace

TEST_CASE("a large-amplitude swing has the exact period 4·sqrt(I/(m g d))·K(sin(θ0/2))", "[hard]") {
  const auto arm = models::robot_arm(P);
  const double I = P.Jz + P.m * P.d * P.d;
  for (double theta0 : {0.5, 2.0, 3.0, 3.1}) {  // up to 178° from hanging
    const double exact = 4 * std::sqrt(I / (P.m * P.g * P.d)) * boost::math::ellint_1(std::sin(theta0 / 2));
    auto st = odeint::make_dense_output(1e-13, 1e-13, odeint::runge_kutta_dopri5<A>());
    st.initialize(A{theta0 - pi / 2, 0.0}, 0.0, 1e-4);  // φ = θ − π/2, at rest
    // From rest at +θ0 the rate turns negative, stops at −θ0 (half period),
    // then stops again at +θ0: the period.
    st.do_step(arm);
    const double half = next_turn(arm, st, -1);
    const double period = next_turn(arm, st, +1);
    test::consistency c;
    A x;
    for (double t : {0.25 * half, half, 1.5 * half, period}) {
      st.calc_state(t, x);
      c.sample(arm, t, x);
    }
    CHECK(c.orthogonality <= 1e-12);
    CHECK(c.residual <= 1e-9);
    CHECK(c.algorithms <= 1e-10);
    INFO("θ0 = " << theta0 << ": period " << period << ", relative error " << (period - exact) / exact);
    // dopri5 at 1e-13 over one period: the crossing time is good to ~1e-12
    // relative; 1e-8 is the bar.
    CHECK(std::abs(period - exact) <= 1e-8 * exact);
  }
}

TEST_CASE("with just enough energy the arm passes over the top, with just too little it does not", "[hard]") {
  const auto arm = models::robot_arm(P);
  const double I = P.Jz + P.m * P.d * P.d, top = 2 * P.m * P.g * P.d;  // energy needed from hanging to upright
  for (double excess : {1e-6, -1e-6}) {
    A x{-pi / 2, std::sqrt(2 * top * (1 + excess) / I)};  // hanging, with the rate for that energy
    double max_phi = x[0];
    test::consistency c;
    odeint::integrate_const(odeint::make_dense_output(1e-13, 1e-13, odeint::runge_kutta_dopri5<A>()), arm, x, 0.0,
                            10.0, 1e-3, [&](const A& s, double t) {
                              max_phi = std::max(max_phi, s[0]);
                              if (int(t * 1000 + 0.5) % 100 == 0) c.sample(arm, t, s);
                            });
    CHECK(c.orthogonality <= 1e-12);
    CHECK(c.residual <= 1e-9);
    CHECK(c.algorithms <= 1e-10);
    INFO("energy excess " << excess << ": largest φ " << max_phi);
    if (excess > 0) CHECK(max_phi > 3 * pi / 2);   // past upright (φ = π/2) and on around
    else CHECK(max_phi < pi / 2);                  // turns back before upright
  }
}

TEST_CASE("released 1e-9 rad from upright, double and long double fall together", "[hard]") {
  const auto arm = models::robot_arm(P);
  const double phi0 = pi / 2 - 1e-9;  // the same double start for both
  // Dense output and bisection for the time the arm is 1 rad below upright.
  auto fall_time = [&](auto zero, auto tol) {
    using T = decltype(zero);
    using X = std::array<T, 2>;
    auto st = odeint::make_dense_output<odeint::runge_kutta_dopri5<X, T>>(tol, tol);
    st.initialize(X{T(phi0), T(0)}, T(0), T(1e-3));
    const T threshold = T(pi / 2 - 1);
    while (true) {
      const auto [t0, t1] = st.do_step(arm);
      if (st.current_state()[0] <= threshold) {
        T lo = t0, hi = t1;
        X x;
        for (int i = 0; i < 100; ++i) {
          const T mid = (lo + hi) / 2;
          st.calc_state(mid, x);
          (x[0] > threshold ? lo : hi) = mid;
        }
        return static_cast<double>((lo + hi) / 2);
      }
    }
  };
  const double td = fall_time(0.0, 1e-14), tl = fall_time(0.0L, 1e-18L);
  {
    // Consistency along the double fall.
    test::consistency c;
    A x{phi0, 0.0};
    odeint::integrate_const(odeint::make_dense_output(1e-14, 1e-14, odeint::runge_kutta_dopri5<A>()), arm, x, 0.0, td,
                            td / 20, [&](const A& s, double t) { c.sample(arm, t, s); });
    CHECK(c.orthogonality <= 1e-12);
    CHECK(c.residual <= 1e-9);
    CHECK(c.algorithms <= 1e-10);
  }
  const double lambda = std::sqrt(P.m * P.g * P.d / (P.Jz + P.m * P.d * P.d));
  INFO("fall time double " << td << ", long double " << tl << ", relative difference " << (td - tl) / tl
                            << ", linearised estimate " << std::log(2.0 / 1e-9) / lambda);
  // Near upright the double state φ ≈ π/2 carries absolute errors of about
  // 1e-14 (the tolerance) against a deviation of 1e-9: a relative error of
  // ~1e-5 in the deviation, which shifts the fall time by ~1e-5/λ (~1e-6
  // relative). The long-double solve (1e-18) has no such floor. So the two
  // agree to 1e-6 relative (measured: 6e-8), and both sit near the
  // linearised estimate ln(2/ε)/λ (within 10%: the nonlinear end of the fall).
  CHECK(std::abs(td - tl) <= 1e-6 * tl);
  CHECK(std::abs(td * lambda / std::log(2.0 / 1e-9) - 1) < 0.1);
}

TEST_CASE("a rotor spun through 10⁴ revolutions keeps its energy and its cut force", "[hard]") {
  auto rotor = scene(World<"world", gravity_kind::none>{}, Revolute<"joint", axis::z>{},
                     FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
                     Body<"mass">({.m = 1.0, .J = Vec3d(0.01, 0.02, 0.02).asDiagonal()}),
                     connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                     connect<"rod.frame_b", "mass.frame_a">);
  const double w = 2 * pi * 100, T = 100;  // 100 rev/s for 100 s
  A x{0.0, w};
  const double e0 = recover(rotor, 0.0, x).energy();
  // Exactly 10⁶ steps (integrate_const may drop the last step to rounding of t).
  odeint::integrate_n_steps(odeint::runge_kutta4<A>(), rotor, x, 0.0, T / 1000000, 1000000);
  const auto sol = recover(rotor, T, x);
  const double force = sol.cut_at("joint.frame_b").f.norm();
  INFO("angle error " << x[0] - w * T << " rad after " << w * T << " rad, energy error " << (sol.energy() - e0) / e0
                      << ", bearing force relative error " << (force - 0.5 * w * w) / (0.5 * w * w));
  // A free rotor: φ̇ stays exactly constant in exact arithmetic and the
  // derivative is exactly 0, so RK4 adds only rounding to the angle (10⁶ steps
  // of ulp(6.3e4) ≈ 7e-12 each, at worst 1e-5 in all). Energy and the
  // centripetal force m·d·ω² depend on φ̇ alone: no loss from the huge angle.
  test::consistency c;
  c.sample(rotor, T, x);
  INFO("after 1e4 revolutions: orthogonality " << c.orthogonality << ", residual " << c.residual);
  CHECK(c.orthogonality <= 1e-12);
  CHECK(c.residual <= 1e-9);
  CHECK(c.algorithms <= 1e-10);
  CHECK(std::abs(x[0] - w * T) <= 1e-5);
  CHECK(std::abs(sol.energy() - e0) <= 1e-14 * e0);
  CHECK(std::abs(force - 1.0 * 0.5 * w * w) <= 1e-12 * force);
}

TEST_CASE("extreme parameters stay finite and agree with the closed forms", "[hard]") {
  std::mt19937 rng(31);
  SECTION("gantry crane with m/M from 1e-8 to 1e8") {
    for (double ratio : {1e-8, 1e-4, 1.0, 1e4, 1e8}) {
      const models::gantry_crane_params p{.M = 1.0, .m = ratio, .d = 0.7, .g = 9.81};
      const double f = 2.0;
      const auto crane = models::gantry_crane(p, f);
      for (int k = 0; k < 20; ++k) {
        std::array<double, 4> x, dx;
        for (auto& v : x) v = test::uniform(rng, -3, 3);
        crane(x, dx, 0.0);
        const auto ref = models::gantry_crane_accelerations(p, f, x[1] + pi / 2, x[3]);
        const double den = p.M + p.m * std::pow(std::sin(x[1] + pi / 2), 2);
        const double num = std::abs(f) + (p.g + p.d * x[3] * x[3]) * (p.m + p.M);
        INFO("m/M = " << ratio);
        // The mass matrix's condition number grows with the ratio (~ max(m/M,
        // M/m) near the vertical), so the tolerance carries it.
        const double cond = std::max(ratio, 1 / ratio);
        CHECK(std::isfinite(dx[2]));
        CHECK(std::abs(dx[2] - ref.s_dd) <= 1e-12 * cond * num / den);
        CHECK(std::abs(dx[3] - ref.theta_dd) <= 1e-12 * cond * num / (p.d * den));
      }
    }
  }
  SECTION("robot arm with lengths and inertias from 1e-6 to 1e6") {
    for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
      const models::robot_arm_params p{.m = 2.0, .d = scale, .Jx = 0.5 * scale * scale, .Jz = 0.4 * scale * scale, .g = 9.81};
      const double Mz = scale;
      const auto arm = models::robot_arm(p, Vec3d(0, 0, Mz));
      for (int k = 0; k < 20; ++k) {
        const A x{test::uniform(rng, -4, 4), test::uniform(rng, -4, 4)};
        A dx;
        arm(x, dx, 0.0);
        const double ref = models::robot_arm_theta_dd(p, Mz, x[0] + pi / 2);
        const double terms = (std::abs(Mz) + p.m * p.d * p.g) / (p.Jz + p.m * p.d * p.d);
        INFO("scale " << scale);
        CHECK(std::isfinite(dx[1]));
        CHECK(std::abs(dx[1] - ref) <= 1e-12 * terms);
      }
    }
  }
}

namespace {
/// Integrates a chaotic scene in double (dopri5, 1e-13) and long double
/// (1e-18) for 20 s: the energy error, consistency along the way, and when
/// the double solve leaves the long-double one by 1e-3 rad.
template <class S, class X, class L>
void chaotic(const S& s, X x, L xl, const char* what) {
  const double e0 = recover(s, 0.0, x).energy();
  double worst_energy = 0, first_divergence = -1;
  test::consistency c;
  auto st = odeint::make_dense_output(1e-13, 1e-13, odeint::runge_kutta_dopri5<X>());
  auto stl = odeint::make_dense_output<odeint::runge_kutta_dopri5<L, long double>>(1e-18L, 1e-18L);
  st.initialize(x, 0.0, 1e-4);
  stl.initialize(xl, 0.0L, 1e-4L);
  constexpr int n = S::n_q;
  for (int k = 1; k <= 2000; ++k) {  // every 10 ms for 20 s
    const double t = 0.01 * k;
    while (st.current_time() < t) st.do_step(s);
    while (stl.current_time() < t) stl.do_step(s);
    st.calc_state(t, x);
    stl.calc_state(t, xl);
    worst_energy = std::max(worst_energy, std::abs(recover(s, t, x).energy() - e0) / std::abs(e0));
    if (k % 50 == 0) c.sample(s, t, x);
    double diff = 0;
    for (int i = 0; i < n; ++i) diff = std::max(diff, std::abs(x[i] - static_cast<double>(xl[i])));
    if (diff > 1e-3 && first_divergence < 0) first_divergence = t;
  }
  INFO(what << ": worst relative energy error " << worst_energy
            << "; double leaves the long-double solve (by 1e-3 rad) at t = " << first_divergence);
  CHECK(worst_energy < 1e-10);
  CHECK(c.orthogonality <= 1e-12);
  CHECK(c.residual <= 1e-9);
  CHECK(c.algorithms <= 1e-10);
  // Errors of ~1e-13 grow like e^{λt}; with λ of a few 1/s they reach 1e-3 rad
  // after ln(1e10)/λ ≈ 5–10 s. Agreement is required up to 4 s.
  CHECK((first_divergence < 0 || first_divergence > 4.0));
}
}  // namespace

TEST_CASE("a chaotic double pendulum conserves energy and follows the long-double solve to a justified horizon", "[hard]") {
  models::chain_params<2> p;
  for (int i = 0; i < 2; ++i) {
    p.axis[i] = Vec3d::UnitZ();
    p.d[i] = Vec3d(0.5, 0, 0);
    p.m[i] = 1.0;
    p.J[i] = Vec3d(0.001, 0.002, 0.002).asDiagonal();
  }
  const auto dp = models::chain<2, models::planar_axes>(p);
  chaotic(dp, std::array<double, 4>{2.0, 2.5, 0.0, 0.0}, std::array<long double, 4>{2.0L, 2.5L, 0.0L, 0.0L},
          "double pendulum");  // both links high: chaotic
}

TEST_CASE("a chaotic branched pendulum (two pendulums on one) does the same", "[hard]") {
  // A "Y": one link on the World, two links on its tip, all turning about z.
  const auto y = scene(World<"world">{}, Revolute<"j0", axis::z>{}, FixedTranslation<"r0">({.d = {0.5, 0, 0}}),
                       Body<"b0">({.m = 1.0, .J = Vec3d(0.001, 0.002, 0.002).asDiagonal()}),
                       Revolute<"j1", axis::z>{}, FixedTranslation<"r1">({.d = {0.4, 0, 0}}),
                       Body<"b1">({.m = 0.7, .J = Vec3d(0.001, 0.002, 0.002).asDiagonal()}),
                       Revolute<"j2", axis::z>{}, FixedTranslation<"r2">({.d = {0.3, 0.1, 0}}),
                       Body<"b2">({.m = 0.5, .J = Vec3d(0.001, 0.002, 0.002).asDiagonal()}),
                       connect<"world.frame_b", "j0.frame_a">, connect<"j0.frame_b", "r0.frame_a">,
                       connect<"r0.frame_b", "b0.frame_a">, connect<"r0.frame_b", "j1.frame_a">,
                       connect<"r0.frame_b", "j2.frame_a">, connect<"j1.frame_b", "r1.frame_a">,
                       connect<"r1.frame_b", "b1.frame_a">, connect<"j2.frame_b", "r2.frame_a">,
                       connect<"r2.frame_b", "b2.frame_a">);
  chaotic(y, std::array<double, 6>{2.0, 2.5, -1.0, 0.0, 0.0, 0.0},
          std::array<long double, 6>{2.0L, 2.5L, -1.0L, 0.0L, 0.0L, 0.0L}, "branched pendulum");
}

TEST_CASE("the free arm over 10⁴ periods: energy drift stays bounded with dopri5 at 1e-10", "[hard]") {
  const auto arm = models::robot_arm(P);
  const double I = P.Jz + P.m * P.d * P.d, theta0 = 1.0;
  const double period = 4 * std::sqrt(I / (P.m * P.g * P.d)) * boost::math::ellint_1(std::sin(theta0 / 2));
  A x{theta0 - pi / 2, 0.0};
  const double e0 = recover(arm, 0.0, x).energy(), scale = 2 * P.m * P.g * P.d;
  budget b;
  test::consistency c;
  double worst = 0;
  const double T = 1e4 * period;
  const std::size_t steps = odeint::integrate_const(
      odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<A>()), checked(arm, b), x, 0.0, T,
      100 * period, [&](const A& s, double t) {
        worst = std::max(worst, std::abs(recover(arm, t, s).energy() - e0) / scale);
        c.sample(arm, t, s);
      });
  INFO(steps << " steps, " << b.rhs_evals << " evaluations over " << T << " s; worst energy drift " << worst
             << " of 2·m·g·d");
  // dopri5 is not symplectic: its energy error random-walks or drifts with
  // the local errors, each ≤ 1e-10 (tolerance) per step; over ~10⁶ steps a
  // linear drift would stay below 1e-10 × steps × the energy scale.
  CHECK(worst <= 1e-10 * double(b.rhs_evals) / 6);
  CHECK(c.orthogonality <= 1e-12);
  CHECK(c.residual <= 1e-9);
  CHECK(c.algorithms <= 1e-10);
}

TEST_CASE("a free body spun at 1e3 rad/s through 1e4 revolutions keeps R orthogonal, its quaternion norm and its energy", "[hard]") {
  // Spin about the axis of largest inertia with a small wobble (stable), no
  // gravity; R comes from the quaternion in homogeneous form, so it is
  // orthogonal to round-off whatever |Q|; |Q| itself drifts only with the
  // integration error.
  const Vec3d I(0.1, 0.2, 0.3);
  const auto s = scene(World<"world", gravity_kind::none>{}, FreeMotion<"fly">{},
                       Body<"body", cm::at_frame, inertia_kind::diagonal>({.m = 1.0, .J = I.asDiagonal()}),
                       connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "body.frame_a">);
  using X = decltype(s)::state_type;
  auto x = neutral_state(s);
  set_joint<"fly">(s, x, {.R = orientation::cardan(0.2, 0.1, 0.3), .w = Vec3d(3, -2, 1e3)});
  const double T = 1e4 * 2 * pi / 1e3;
  const double e0 = recover(s, 0.0, x).kinetic;
  double worst_orth = 0, worst_norm = 0, worst_e = 0;
  budget b;
  odeint::integrate_const(odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), checked(s, b), x,
                          0.0, T, T / 100, [&](const X& y, double t) {
                            const Mat3d R = quaternion::to_rotation(y.data() + 3);
                            worst_orth = std::max(worst_orth, (R * R.transpose() - Mat3d::Identity()).cwiseAbs().maxCoeff());
                            worst_norm = std::max(worst_norm, std::abs(Eigen::Vector4d(y[3], y[4], y[5], y[6]).norm() - 1));
                            worst_e = std::max(worst_e, std::abs(recover(s, t, y).kinetic - e0) / e0);
                          });
  INFO(b.rhs_evals << " evaluations; |R·R' − 1| " << worst_orth << ", | |Q| − 1 | " << worst_norm << ", energy "
                   << worst_e);
  CHECK(worst_orth <= 1e-12);
  // dopri5's local errors (≤ 1e-10 relative per step) accumulate over the
  // ~10⁵ steps: the norm and the energy stay within 1e-10 × steps.
  CHECK(worst_norm <= 1e-10 * double(b.rhs_evals) / 6);
  CHECK(worst_e <= 1e-10 * double(b.rhs_evals) / 6);
  // normalize() projects |Q| back to 1 between steps.
  normalize(s, x);
  CHECK(std::abs(Eigen::Vector4d(x[3], x[4], x[5], x[6]).norm() - 1) <= 1e-15);
}
