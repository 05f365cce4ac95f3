// The 3-D joints with every Boost.Odeint stepper that works today: a scene
// holding each of them (Spherical, Universal, Cylindrical, Planar, a
// FixedRotation, and a FreeMotion on the World) reaches a tight reference
// with each explicit stepper and with rosenbrock4 on the exact dual-number
// Jacobian, which agrees with central differences; the residual on the
// recovered variables vanishes along the way.
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

#include "consistency.hpp"

using namespace flange;

namespace {
const Mat3d J = Vec3d(0.02, 0.03, 0.04).asDiagonal();
auto every_joint() {
  return scene(World<"world">{}, Spherical<"ball">{}, FixedTranslation<"arm">({.d = {0, -0.4, 0.1}}),
               Body<"b1">({.m = 1.0, .J = J}), Universal<"cardan">({.n_a = {1, 0, 0}, .n_b = {0, 0, 1}}),
               FixedRotation<"turn">({.r = {0.1, -0.3, 0}, .R = orientation::rpy(0.2, -0.1, 0.4)}),
               Body<"b2">({.m = 0.8, .J = J}), Cylindrical<"sleeve">({.n = {0.2, 1, 0.1}}),
               Body<"b3">({.m = 0.5, .J = J}), Planar<"slide">({.n = {0, 0, 1}, .n_x = {1, 0, 0}}),
               Body<"b4", cm::offset>({.m = 0.4, .J = J, .r_cm = {0.05, 0, 0}}), FreeMotion<"fly">{},
               Body<"b5">({.m = 0.6, .J = J}), SpringDamper<"tether">({.c = 20, .s0 = 0.3, .d = 0.5}),
               connect<"world.frame_b", "ball.frame_a">, connect<"ball.frame_b", "arm.frame_a">,
               connect<"arm.frame_b", "b1.frame_a">, connect<"arm.frame_b", "cardan.frame_a">,
               connect<"cardan.frame_b", "turn.frame_a">, connect<"turn.frame_b", "b2.frame_a">,
               connect<"turn.frame_b", "sleeve.frame_a">, connect<"sleeve.frame_b", "b3.frame_a">,
               connect<"sleeve.frame_b", "slide.frame_a">, connect<"slide.frame_b", "b4.frame_a">,
               connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b5.frame_a">,
               connect<"b5.frame_a", "tether.frame_a">, connect<"b4.frame_a", "tether.frame_b">);
}
using S = decltype(every_joint());
using X = S::state_type;

X start(const S& s) {
  auto x = neutral_state(s);
  set_joint<"ball">(s, x, {.R = orientation::cardan(0.3, 0.1, -0.2), .w = Vec3d(0.5, -1, 0.3)});
  set_joint<"cardan">(s, x, {.q = {0.2, -0.4}, .v = {1, 0.5}});
  set_joint<"sleeve">(s, x, {.q = {0.1, 0.3}, .v = {0.2, -1}});
  set_joint<"slide">(s, x, {.q = {0.1, 0.05, 0.4}, .v = {0.3, 0, 1}});
  set_joint<"fly">(s, x, {.r = Vec3d(0.5, -0.5, 0.2), .v = Vec3d(0, 1, 0), .R = orientation::axis_angle(Vec3d(1, 2, 3), 0.7),
                          .w = Vec3d(2, 0, -1)});
  return x;
}
double distance(const X& a, const X& b) {
  double d = 0;
  for (int i = 0; i < S::n_state; ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}
constexpr double T = 1.0;
}  // namespace

TEST_CASE("every explicit stepper and rosenbrock4 integrate the 3-D joints to the tight reference") {
  const auto s = every_joint();
  static_assert(S::n_q == 4 + 2 + 2 + 3 + 7 && S::n_v == 3 + 2 + 2 + 3 + 6);
  static_assert(S::n_equations == S::n_unknowns);
  X ref = start(s);
  odeint::integrate_adaptive(odeint::make_controlled(1e-14, 1e-14, odeint::runge_kutta_fehlberg78<X>()), s, ref, 0.0,
                             T, 1e-4);
  auto run = [&](const char* name, auto integrate, double bar) {
    X x = start(s);
    integrate(x);
    INFO(name << ": distance from the reference " << distance(x, ref));
    CHECK(distance(x, ref) < bar);
  };
  // Controlled steppers at 1e-10 over 1 s: the global error stays below 1e-7.
  run("runge_kutta4, h = 5e-4", [&](X& x) { odeint::integrate_const(odeint::runge_kutta4<X>(), s, x, 0.0, T, 5e-4); },
      1e-7);
  run("cash_karp54", [&](X& x) {
        odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_cash_karp54<X>()), s, x,
                                   0.0, T, 1e-3);
      },
      1e-7);
  run("dopri5", [&](X& x) {
        odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), s, x, 0.0,
                                   T, 1e-3);
      },
      1e-7);
  run("fehlberg78", [&](X& x) {
        odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_fehlberg78<X>()), s, x,
                                   0.0, T, 1e-3);
      },
      1e-7);
  run("bulirsch_stoer", [&](X& x) {
        odeint::bulirsch_stoer<X> bs(1e-10, 1e-10);
        odeint::integrate_adaptive(bs, s, x, 0.0, T, 1e-3);
      },
      1e-7);
  run("adams_bashforth_moulton<5>, h = 5e-4",
      [&](X& x) { odeint::integrate_const(odeint::adams_bashforth_moulton<5, X>(), s, x, 0.0, T, 5e-4); }, 1e-7);
  run("rosenbrock4 (exact Jacobian)", [&](X& x) { integrate_rosenbrock4(s, x, 0.0, T, 1e-3, 1e-10, 1e-10); }, 1e-7);
}

TEST_CASE("the dual-number Jacobian of the 3-D joints agrees with central differences") {
  const auto s = every_joint();
  const X x = start(s);
  Eigen::Matrix<double, S::n_state, 1> ft, ft_fd;
  const auto Jx = jacobian(s, 0.3, x, &ft);
  const auto Jfd = jacobian_finite_difference(s, 0.3, x, &ft_fd);
  // Central differences carry ~1e-10 relative error (h = ε^(1/3)).
  const double scale = std::max(1.0, Jx.cwiseAbs().maxCoeff());
  INFO("largest difference " << (Jx - Jfd).cwiseAbs().maxCoeff() << " of " << scale);
  CHECK((Jx - Jfd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
}

TEST_CASE("the residual vanishes along a trajectory of the 3-D joints") {
  const auto s = every_joint();
  X x = start(s);
  test::consistency c;
  odeint::integrate_const(odeint::make_dense_output(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, 2.0,
                          0.1, [&](const X& y, double t) { c.sample(s, t, y); });
  INFO("orthogonality " << c.orthogonality << ", residual " << c.residual << ", NE − ABA " << c.algorithms);
  CHECK(c.orthogonality <= 1e-12);
  CHECK(c.residual <= 1e-12);
  CHECK(c.algorithms <= 1e-10);
}
