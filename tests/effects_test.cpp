// The effects a scene's type switches on or off: joint friction against closed
// forms and through the residual, point masses, and every specialised variant
// against its general form (the same numbers to round-off).
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/gimbal.hpp>
#include <flange/simulate/odeint.hpp>

#include "consistency.hpp"
#include "random_params.hpp"

using namespace flange;

namespace {
const Mat3d J = Vec3d(0.01, 0.02, 0.02).asDiagonal();
constexpr double I = 0.02 + 1.0 * 0.25;  // J_z + m·l² about the joint

/// The paper's arm with its axis law and gravity chosen by type.
template <class Law, class Gravity = gravity_kind::uniform, class Axis = axis::z>
auto arm(typename Revolute<"joint", Axis, Law>::params p) {
  return scene(World<"world", Gravity>{}, Revolute<"joint", Axis, Law>(p), FixedTranslation<"rod">({.d = {0.5, 0, 0}}),
               Body<"mass">({.m = 1.0, .J = J}), connect<"world.frame_b", "joint.frame_a">,
               connect<"joint.frame_b", "rod.frame_a">, connect<"rod.frame_b", "mass.frame_a">);
}

template <class A, class B>
double max_difference(const A& a, const B& b, std::mt19937& rng) {
  using X = typename A::state_type;
  double worst = 0;
  for (int k = 0; k < 50; ++k) {
    X x, da, db;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    a(x, da, 0.2);
    b(x, db, 0.2);
    for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(da[i] - db[i]) / (1 + std::abs(db[i])));
  }
  return worst;
}
}  // namespace

TEST_CASE("viscous joint friction decays the rate exponentially") {
  // No gravity: I·φ̈ = −d·φ̇, so φ̇ = φ̇0·e^{−d t / I}, φ = φ0 + φ̇0·I/d·(1 − e^{−d t / I}).
  const double d = 0.05;
  const auto s = arm<axis_law::friction, gravity_kind::none>({.d = d, .f_c = 0.0});
  using X = decltype(s)::state_type;
  X x{0.3, 2.0};
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, 5.0, 1e-3);
  const double e = std::exp(-d * 5.0 / I);
  // dopri5 at 1e-12 over ~10² steps: global error well below 1e-9.
  CHECK(std::abs(x[1] - 2.0 * e) < 1e-9);
  CHECK(std::abs(x[0] - (0.3 + 2.0 * I / d * (1 - e))) < 1e-9);
}

TEST_CASE("Coulomb joint friction decelerates at the constant rate F_c / I") {
  // With |φ̇| ≫ v_s, tanh(φ̇/v_s) = 1 to double precision (1 − 2e^{−2φ̇/v_s}),
  // so φ̈ = −F_c / I exactly while φ̇ > 0.5: φ̇ = φ̇0 − (F_c/I)·t.
  const double fc = 0.1;
  const auto s = arm<axis_law::friction, gravity_kind::none>({.d = 0.0, .f_c = fc, .v_s = 1e-6});
  using X = decltype(s)::state_type;
  X x{0.0, 3.0};
  const double T = 2.0;  // φ̇(T) = 3 − 0.37·2 ≈ 2.26
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, T, 1e-3);
  CHECK(std::abs(x[1] - (3.0 - fc / I * T)) < 1e-10);
  CHECK(std::abs(x[0] - (3.0 * T - 0.5 * fc / I * T * T)) < 1e-10);
}

TEST_CASE("a friction pendulum loses exactly the energy its friction dissipates, and satisfies its residual") {
  const double d = 0.02, fc = 0.05, vs = 1e-2;
  const auto s = arm<axis_law::friction>({.d = d, .f_c = fc, .v_s = vs});
  using X = decltype(s)::state_type;
  // Integrate the dissipated power d·φ̇² + F_c·φ̇·tanh(φ̇/v_s) beside the state.
  using Y = std::array<double, 3>;
  auto augmented = [&](const Y& y, Y& dy, double t) {
    X x{y[0], y[1]}, dx;
    s(x, dx, t);
    dy = {dx[0], dx[1], d * y[1] * y[1] + fc * y[1] * std::tanh(y[1] / vs)};
  };
  Y y{0.5, 0.0, 0.0};
  const double E0 = recover(s, 0.0, X{y[0], y[1]}).energy();
  double worst_residual = 0;
  for (int k = 1; k <= 20; ++k) {
    odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<Y>()), augmented, y,
                               0.25 * (k - 1), 0.25 * k, 1e-3);
    worst_residual = std::max(worst_residual, scaled_residual(s, recover(s, 0.25 * k, X{y[0], y[1]})));
  }
  const double E = recover(s, 5.0, X{y[0], y[1]}).energy();
  INFO("energy " << E0 << " -> " << E << ", dissipated " << y[2]);
  CHECK(y[2] > 0.1);                                   // friction did real work
  CHECK(std::abs(E0 - E - y[2]) < 1e-9 * std::abs(E0));  // power balance, to the integration error
  CHECK(worst_residual < 1e-12);  // M₂·n = d·φ̇ + F_c·tanh(φ̇/v_s) holds on the recovered variables
}

TEST_CASE("friction parameters are checked at construction") {
  CHECK_THROWS_WITH((Revolute<"knee", axis::z, axis_law::friction>({.d = -1.0})),
                    Catch::Contains("Revolute \"knee\": friction d = -1") && Catch::Contains("must not be negative"));
  CHECK_THROWS_WITH((Revolute<"knee", axis::z, axis_law::friction>({.f_c = 0.1, .v_s = 0.0})),
                    Catch::Contains("Revolute \"knee\": friction v_s = 0 must be positive"));
  CHECK_THROWS_WITH((Revolute<"knee", axis::z, axis_law::friction>({.f_c = std::nan("")})),
                    Catch::Contains("Revolute \"knee\": parameter f_c (Coulomb friction) is not finite"));
}

TEST_CASE("a point mass is a body without rotational inertia") {
  const auto body = models::gantry_crane();  // its load is Body<"load">({.m = 0.5}): J = 0 by value
  const auto point = scene(World<"world">{}, Prismatic<"rail", axis::x>({}),
                           Body<"cart">({.m = 1.0, .J = Mat3d::Identity() * 0.1}), Revolute<"pivot", axis::z>{},
                           FixedTranslation<"rope">({.d = {1.0, 0, 0}}), PointMass<"load">({.m = 0.5}),
                           connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
                           connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rope.frame_a">,
                           connect<"rope.frame_b", "load.frame_a">);
  STATIC_REQUIRE(decltype(point)::n_equations == decltype(body)::n_equations);
  std::mt19937 rng(3);
  CHECK(max_difference(point, body, rng) == 0.0);  // the same link constants, the same arithmetic
  const auto sol = recover(point, 0.0, std::array<double, 4>{0.1, -0.7, 0.4, 1.3});
  CHECK(sol.cut_at("load.frame_a").n.norm() == 0.0);
  CHECK(scaled_residual(point, sol) < 1e-14);
  CHECK_THROWS_WITH(PointMass<"load">({.m = 0.5, .J = Mat3d::Identity()}),
                    Catch::Contains("Body \"load\": a point mass has no rotational inertia"));
}

TEST_CASE("every specialised variant gives the numbers of its general form") {
  std::mt19937 rng(5);
  // Gravity removed by type against gravity zero by value.
  CHECK(max_difference(arm<axis_law::none, gravity_kind::none>({}),
                       scene(World<"world">({.g = Vec3d::Zero()}), Revolute<"joint", axis::z>{},
                             FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1.0, .J = J}),
                             connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                             connect<"rod.frame_b", "mass.frame_a">),
                       rng) == 0.0);
  // No axis law against a spring-damper and friction of zero.
  const auto plain = arm<axis_law::none>({});
  CHECK(max_difference(plain, arm<axis_law::spring_damper>({.c = 0.0, .d = 0.0}), rng) == 0.0);
  CHECK(max_difference(plain, arm<axis_law::friction>({.d = 0.0, .f_c = 0.0}), rng) == 0.0);
  // The axis z by type against z by value (2-D against 3-D rotations, and
  // planar against spatial arithmetic): equal to round-off.
  CHECK(max_difference(plain, arm<axis_law::none, gravity_kind::uniform, axis::any>({.n = Vec3d::UnitZ()}), rng) <
        1e-14);
  const auto crane = models::gantry_crane({}, 0.3);
  const auto crane_any = scene(
      World<"world">{}, Prismatic<"rail">({.n = Vec3d::UnitX(), .f = 0.3}), Body<"cart">({.m = 1.0, .J = Mat3d::Identity() * 0.1}),
      Revolute<"pivot">({.n = Vec3d::UnitZ()}), FixedTranslation<"rope">({.d = {1.0, 0, 0}}), Body<"load">({.m = 0.5}),
      connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
      connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rope.frame_a">,
      connect<"rope.frame_b", "load.frame_a">);
  CHECK(max_difference(crane, crane_any, rng) < 1e-14);
}

TEST_CASE("a prismatic joint's spring-damper and friction laws against closed forms and the residual") {
  // A cart on a rail along x without gravity: m·s̈ = −c·(s − s0) − d·ṡ + f.
  const double m = 2.0, c = 8.0, d = 0.4, s0 = 0.3, f = 0.5;
  auto rail = [&](auto joint) {
    return scene(World<"world", gravity_kind::none>{}, joint, PointMass<"cart">({.m = m}),
                 connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">);
  };
  const auto sd = rail(Prismatic<"rail", axis::x, double, axis_law::spring_damper>({.f = f, .c = c, .d = d, .s0 = s0}));
  using X = decltype(sd)::state_type;
  // Equilibrium s* = s0 + f/c; underdamped approach from s(0) = 1, ṡ(0) = 0.
  const double se = s0 + f / c, w = std::sqrt(c / m), zeta = d / (2 * std::sqrt(c * m)),
               wd = w * std::sqrt(1 - zeta * zeta), A = 1.0 - se, B = zeta * w * A / wd, T = 4.0;
  X x{1.0, 0.0};
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), sd, x, 0.0, T, 1e-3);
  CHECK(std::abs(x[0] - (se + std::exp(-zeta * w * T) * (A * std::cos(wd * T) + B * std::sin(wd * T)))) < 1e-9);
  CHECK(scaled_residual(sd, recover(sd, T, x)) < 1e-13);

  // Coulomb friction F_c larger than the push f: while ṡ ≫ v_s, m·s̈ = f − F_c.
  const double fc = 1.5;
  const auto fr = rail(Prismatic<"rail", axis::x, double, axis_law::friction>({.f = f, .f_c = fc, .v_s = 1e-6}));
  X y{0.0, 2.0};
  const double Tf = 1.5;  // ṡ(T) = 2 − 0.5·1.5 = 1.25 > 0
  odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()), fr, y, 0.0, Tf, 1e-3);
  CHECK(std::abs(y[1] - (2.0 + (f - fc) / m * Tf)) < 1e-10);
  CHECK(scaled_residual(fr, recover(fr, Tf, y)) < 1e-13);
  CHECK_THROWS_WITH((Prismatic<"rail", axis::x, double, axis_law::spring_damper>({.c = -2.0})),
                    Catch::Contains("Prismatic \"rail\": spring-damper c = -2"));
}

TEST_CASE("bodies at their links' origins: diagonal and point inertias known from the type give the general numbers") {
  const auto typed = models::gimbal<inertia_kind::diagonal, inertia_kind::point>();
  // The same J, and J = 0, as values.
  const auto general = models::gimbal<inertia_kind::full, inertia_kind::full>(Vec3d::Zero());
  using F = detail::inertia_kinds<std::remove_cvref_t<decltype(typed)>>;
  STATIC_REQUIRE(F::value.I_kind[1] == 1);  // diagonal
  STATIC_REQUIRE(F::value.I_kind[2] == 0);  // a point mass at the origin: no rotational inertia
  STATIC_REQUIRE(F::value.h_zero[1] && F::value.h_zero[2] && F::value.h_zero[3]);
  STATIC_REQUIRE(detail::inertia_kinds<std::remove_cvref_t<decltype(general)>>::value.I_kind[1] == 2);
  std::mt19937 rng(8);
  CHECK(max_difference(typed, general, rng) < 1e-14);
  // And against the articulated-body algorithm, which knows none of this.
  test::consistency along;
  for (int k = 0; k < 20; ++k) {
    std::array<double, 6> x;
    for (auto& v : x) v = test::uniform(rng, -2, 2);
    along.sample(typed, 0.0, x);
  }
  CHECK(along.algorithms < 1e-12);
  CHECK(along.residual < 1e-13);
  CHECK_THROWS_WITH((Body<"b", cm::at_frame, inertia_kind::diagonal>({.m = 1, .J = Mat3d::Identity() + Mat3d::Ones() * 0.01})),
                    Catch::Contains("Body \"b\": declared with a diagonal inertia") && Catch::Contains("products of inertia"));
}
