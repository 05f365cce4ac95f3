// Closed loops against independent references: Freudenstein's equation and
// the slider-crank's closed-form kinematics, energy conservation, constraint
// drift, the parallelogram four-bar through its singular positions against
// its one-degree-of-freedom equivalent pendulum, and the errors for states
// and lengths that cannot close a loop.
#include <boost/numeric/odeint.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>

#include "invariant_scenes.hpp"
#include "loop_laws.hpp"

using namespace flange;
namespace odeint = boost::numeric::odeint;
using X6 = std::array<double, 6>;
constexpr double pi = std::numbers::pi;

namespace {
/// The angle a − b folded into (−π, π].
double angle_diff(double a, double b) { return std::remainder(a - b, 2 * pi); }

/// max |Φ_i| and max |(G·v)_i| at x.
template <class S>
std::pair<double, double> constraint_errors(const S& s, const X6& x) {
  const auto r = loop_residual(s, x);
  return {r.max_phi(), r.max_phid()};
}
}  // namespace

TEST_CASE("a planar four-bar is cut at its last joint into 2 constraints on a 3-joint tree") {
  auto fb = models::fourbar({});
  using S = decltype(fb);
  STATIC_REQUIRE(S::n_q == 3);
  STATIC_REQUIRE(S::tree.n_cuts == 1);
  STATIC_REQUIRE(S::tree.cuts[0] == S::index_of("rocker_pivot"));
  STATIC_REQUIRE(detail::n_constraints<S>() == 2);  // a spatial revolute cut would lock 5
  auto sc = models::slider_crank({});
  STATIC_REQUIRE(detail::n_constraints<decltype(sc)>() == 2);
}

TEST_CASE("the four-bar's rocker angle satisfies Freudenstein's equation at 100 crank angles") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  const double a = p.crank, b = p.coupler, c = p.rocker, d = p.ground;
  const double K1 = d / a, K2 = d / c, K3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
  double worst_angle = 0, worst_equation = 0;
  for (int i = 0; i < 100; ++i) {
    const double th2 = 2 * pi * i / 100;
    const double th4 = models::freudenstein_rocker(p, th2);
    // A guess 0.1 rad off the closed position, then Newton.
    const auto q = models::fourbar_coordinates(p, th2, th4 + 0.1);
    X6 x{q[0], q[1], q[2], 0, 0, 0};
    close_loops<"crank_pivot">(fb, x);
    REQUIRE(x[0] == th2);  // held
    const double rocker = x[0] + x[1] + x[2] - pi;
    worst_angle = std::max(worst_angle, std::abs(angle_diff(rocker, th4)));
    worst_equation = std::max(worst_equation, std::abs(K1 * std::cos(rocker) - K2 * std::cos(th2) + K3 -
                                                       std::cos(th2 - rocker)));
  }
  CHECK(worst_angle < 1e-10);
  CHECK(worst_equation < 1e-10);
}

TEST_CASE("the four-bar's crank acceleration equals the hand-written one-coordinate equation of motion") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  double worst = 0;
  for (int i = 0; i < 100; ++i) {
    const double th2 = 2 * pi * i / 100, w2 = 3.0 - 0.05 * i;
    const auto q = models::fourbar_coordinates(p, th2, models::freudenstein_rocker(p, th2));
    X6 x{q[0], q[1], q[2], w2, 0, 0}, dx;
    close_loops<"crank_pivot">(fb, x);
    fb(x, dx, 0.0);
    const double ref = models::fourbar_crank_acceleration(p, th2, w2);
    worst = std::max(worst, std::abs(dx[3] - ref) / std::max(1.0, std::abs(ref)));
  }
  CHECK(worst < 1e-10);
}

TEST_CASE("a free four-bar conserves energy and keeps its loop closed for 10 s") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  auto x = initial_state<"crank_pivot">(fb, {.q = 1.0, .v = 2.0});
  const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  x[1] = q[1];
  x[2] = q[2];
  close_loops<"crank_pivot">(fb, x);
  const double E0 = recover(fb, 0.0, x).energy();
  double dE = 0, phi = 0, phid = 0;
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
  integrate_projected(stepper, fb, x, 0.0, 10.0, 1e-3, [&](const X6& s, double) {
    dE = std::max(dE, std::abs(recover(fb, 0.0, s).energy() - E0) / std::abs(E0));
    const auto [e, ed] = constraint_errors(fb, s);
    phi = std::max(phi, e);
    phid = std::max(phid, ed);
  });
  CHECK(dE < 1e-9);
  CHECK(phi < 1e-10);
  CHECK(phid < 1e-10);

  SECTION("without projection, the drift stays at the stepper's tolerance") {
    auto y = initial_state<"crank_pivot">(fb, {.q = 1.0, .v = 2.0});
    y[1] = q[1];
    y[2] = q[2];
    close_loops<"crank_pivot">(fb, y);
    double drift = 0;
    odeint::integrate_const(stepper, std::cref(fb), y, 0.0, 10.0, 0.01,
                            [&](const X6& s, double) { drift = std::max(drift, constraint_errors(fb, s).first); });
    CHECK(drift < 1e-10);
  }
}

TEST_CASE("the slider-crank's piston follows the closed-form kinematics") {
  const models::slider_crank_params p;
  auto sc = models::slider_crank(p);
  const int slide = decltype(sc)::q_offset("slide");
  double worst_x = 0, worst_v = 0;
  for (int i = 0; i < 100; ++i) {
    const double th = 2 * pi * i / 100, w = 3.0;
    // The guess: the rod level, the piston at the far dead centre.
    auto x = initial_state<"crank_pivot", "crank_pin", "slide">(sc, {.q = th, .v = w}, {.q = -th},
                                                                {.q = p.crank + p.rod});
    close_loops<"crank_pivot">(sc, x);
    const auto ref = models::piston(p, th);
    worst_x = std::max(worst_x, std::abs(x[slide] - ref.x));
    worst_v = std::max(worst_v, std::abs(x[3 + slide] - ref.dx * w));
  }
  CHECK(worst_x < 1e-10);
  CHECK(worst_v < 1e-10);

  SECTION("the piston's acceleration along a free run, and energy over 10 s") {
    auto x = initial_state<"crank_pivot", "crank_pin", "slide">(sc, {.q = 0.3, .v = 20.0}, {.q = -0.3},
                                                                {.q = p.crank + p.rod});
    close_loops<"crank_pivot">(sc, x);
    const double E0 = recover(sc, 0.0, x).energy();
    double worst_a = 0, dE = 0;
    auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
    integrate_projected(stepper, sc, x, 0.0, 10.0, 1e-3, [&](const X6& s, double t) {
      X6 ds;
      sc(s, ds, t);
      const auto ref = models::piston(p, s[0]);
      // ẍ = x'·θ̈ + x''·θ̇², with θ̈ from the same derivative: the constraint's acceleration level.
      worst_a = std::max(worst_a, std::abs(ds[3 + slide] - (ref.dx * ds[3] + ref.ddx * s[3] * s[3])));
      dE = std::max(dE, std::abs(recover(sc, 0.0, s).energy() - E0) / std::abs(E0));
    });
    // Accelerations here are up to r·θ̇² ≈ 40 m/s²: 1e-10 is a few ulps of them times the condition.
    CHECK(worst_a < 1e-10 * 40);
    CHECK(dE < 1e-9);
  }
}

TEST_CASE("a parallelogram four-bar passes its flat singular positions as its equivalent pendulum") {
  // Crank and rocker of one length, coupler as long as the ground: the
  // coupler translates, so the mechanism is one pendulum of inertia
  // J = m1·a²/3 + m3·c²/3 + m2·a² under the moment g·(m1·a/2 + m3·c/2 + m2·a)·cos θ.
  models::fourbar_params p;
  p.ground = p.coupler = 1.0;
  p.crank = p.rocker = 0.3;
  auto fb = models::fourbar(p);
  const double th0 = 0.3, w0 = 12.0;
  const auto q = models::fourbar_coordinates(p, th0, th0);
  X6 x{q[0], q[1], q[2], w0, -w0, w0};
  check_loops(fb, x);
  const double a = p.crank, c = p.rocker, g = 9.81;
  const double J = p.m_crank * a * a / 3 + p.m_rocker * c * c / 3 + p.m_coupler * a * a;
  const double K = g * (p.m_crank * a / 2 + p.m_rocker * c / 2 + p.m_coupler * a);
  auto pendulum = [&](const std::array<double, 2>& s, std::array<double, 2>& ds, double) {
    ds[0] = s[1];
    ds[1] = -K * std::cos(s[0]) / J;
  };
  std::array<double, 2> y{th0, w0};
  const double E0 = recover(fb, 0.0, x).energy();
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
  auto reference = odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<std::array<double, 2>>());
  double worst = 0, dE = 0, coupler = 0;
  int flat = 0;
  double t = 0;
  for (int k = 1; k <= 2000; ++k) {
    const double t1 = k * 0.01, before = x[0];
    integrate_projected(stepper, fb, x, t, t1, 1e-3);
    odeint::integrate_adaptive(reference, pendulum, y, t, t1, 1e-3);
    t = t1;
    worst = std::max(worst, std::abs(x[0] - y[0]));
    dE = std::max(dE, std::abs(recover(fb, 0.0, x).energy() - E0) / E0);
    coupler = std::max(coupler, std::abs(angle_diff(x[0] + x[1], 0)));
    flat += int(std::floor(x[0] / pi) - std::floor(before / pi));
  }
  CHECK(flat >= 70);       // it passed the lined-up positions that often
  CHECK(coupler < 1e-9);   // and stayed a parallelogram (no switch to the crossed branch)
  // Measured 1.0e-8 and 4.2e-10 (docs/loops.md); each flat position adds
  // round-off that the damped solve absorbs, and the phase error is the
  // energy error's integral, so the bounds sit an order of magnitude above.
  CHECK(worst < 1e-7);
  CHECK(dE < 1e-8);
}

TEST_CASE("a spatial RSUR loop with Spherical and Universal joints conserves energy and stays closed") {
  // The pivot is placed where the open chain puts the rocker's end at a
  // chosen state, about the axis of the rocker's rotation there: that state
  // closes the loop, generically away from singular positions
  // (invariant_scenes.hpp).
  using S = invariant_scenes::Rsur;
  STATIC_REQUIRE(detail::n_constraints<S>() == 5);
  auto closed = invariant_scenes::rsur_closed();  // a lambda cannot capture a structured binding in clang 14
  const auto& sp = closed.scene;
  auto& x = closed.x;
  const double E0 = recover(sp, 0.0, x).energy();
  double dE = 0, drift = 0, residual = 0;
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<S::state_type>());
  integrate_projected(stepper, sp, x, 0.0, 10.0, 1e-3, [&](const S::state_type& s, double t) {
    const auto sol = recover(sp, t, s);
    dE = std::max(dE, std::abs(sol.energy() - E0) / std::abs(E0));
    residual = std::max(residual, scaled_residual(sp, sol));
    const auto r = loop_residual(sp, s);
    drift = std::max({drift, r.max_phi(), r.max_phid()});
  });
  CHECK(dE < 1e-9);  // 2.4e-11 measured
  CHECK(drift < 1e-10);
  CHECK(residual < 1e-12);
}

TEST_CASE("recovery on loop scenes: the residual holds, and the cut forces match a second cut") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  // The same four-bar cut at the rocker's other end: "rocker_pin" written last.
  using models::bar;
  auto other = scene(World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
                     Revolute<"crank_pin", axis::z>{}, bar<"coupler">(p.coupler, p.m_coupler),
                     bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
                     Revolute<"rocker_pivot", axis::z>{}, Revolute<"rocker_pin", axis::z>{},
                     connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
                     connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
                     connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
                     connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "rocker_pivot.frame_a">,
                     connect<"rocker.frame_b", "rocker_pivot.frame_b">);
  STATIC_REQUIRE(decltype(other)::tree.cuts[0] == decltype(other)::index_of("rocker_pin"));
  const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  X6 x{q[0], q[1], q[2], 3.0, 0, 0};
  close_loops<"crank_pivot">(fb, x);
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
  double residual = 0, force = 0, angle = 0;
  integrate_projected(stepper, fb, x, 0.0, 2.0, 1e-3, [&](const X6& s, double t) {
    const auto sol = recover(fb, t, s);
    residual = std::max(residual, scaled_residual(fb, sol));
    // The rocker's angle at its pivot is the other tree's coordinate.
    const X6 y{s[0], s[1], s[0] + s[1] + s[2], s[3], s[4], s[3] + s[4] + s[5]};
    const auto sol2 = recover(other, t, y);
    residual = std::max(residual, scaled_residual(other, sol2));
    for (const char* f : {"rocker_pivot.frame_a", "rocker_pivot.frame_b", "rocker_pin.frame_a", "rocker_pin.frame_b",
                          "crank_pin.frame_b"}) {
      const double scale = std::max(1.0, sol2.cut_at(f).f.norm());
      force = std::max(force, (sol.cut_at(f).f - sol2.cut_at(f).f).norm() / scale);
      force = std::max(force, (sol.cut_at(f).n - sol2.cut_at(f).n).norm() / scale);
    }
    // The cut joint's angle, recovered from its frames, is the other tree's coordinate.
    angle = std::max(angle, std::abs(angle_diff(sol.internal<"rocker_pivot", "phi">(), y[2])));
    angle = std::max(angle, std::abs(angle_diff(sol2.internal<"rocker_pin", "phi">(), s[2])));
  });
  CHECK(residual < 1e-12);
  CHECK(force < 1e-9);
  CHECK(angle < 1e-12);
}

TEST_CASE("rosenbrock4 with the exact Jacobian steps a loop scene") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  X6 x{q[0], q[1], q[2], 2.0, 0, 0};
  close_loops<"crank_pivot">(fb, x);
  X6 ref = x;
  auto stepper = odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X6>());
  odeint::integrate_adaptive(stepper, std::cref(fb), ref, 0.0, 1.0, 1e-3);
  integrate_rosenbrock4(fb, x, 0.0, 1.0, 1e-3, 1e-10, 1e-10);
  for (int i = 0; i < 6; ++i) CHECK(std::abs(x[i] - ref[i]) < 1e-7);
}

TEST_CASE("states and lengths that cannot close a loop are refused, naming the loop") {
  const models::fourbar_params p;
  auto fb = models::fourbar(p);
  auto open = initial_state<"crank_pivot", "crank_pin">(fb, {.q = 1.0}, {.q = -0.5});
  CHECK_THROWS_WITH(check_loops(fb, open), Catch::Contains("leaves the loop closed by Revolute \"rocker_pivot\" open") &&
                                               Catch::Contains("m apart"));
  budget b;
  auto stepper = odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<X6>());
  CHECK_THROWS_WITH(odeint::integrate_adaptive(stepper, checked(fb, b), open, 0.0, 1.0, 1e-3),
                    Catch::Contains("rocker_pivot") && Catch::Contains("at t = 0"));

  models::fourbar_params too_long = p;
  too_long.coupler = 3.0;  // longer than the other three together
  auto bad = models::fourbar(too_long);
  auto x = initial_state<"crank_pivot">(bad, {.q = 1.0});
  CHECK_THROWS_WITH(close_loops<"crank_pivot">(bad, x),
                    Catch::Contains("the loop closed by Revolute \"rocker_pivot\" cannot close near the given state"));
}

TEST_CASE("the spatial RSUR loop's Jacobian: dual numbers, where its loop solve is damped") {
  // jacobian() differentiates a loop implicitly only where its loop solve is
  // the exact one (simulate/jacobian.hpp). The RSUR loop's five cut rows
  // overlap enough that the solve damps them (the largest share the damping
  // leaves out is about 1.2e-3 here, above constraint_sweep_skip's 1e-4, and
  // four sweeps refine it): jacobian() then takes dual numbers through that
  // very solve, so it is jacobian_dual() to the bit.
  using S = invariant_scenes::Rsur;
  auto closed = invariant_scenes::rsur_closed();
  const auto& sp = closed.scene;
  std::mt19937 rng(9);
  for (int k = 0; k < 3; ++k) {
    auto x = closed.x;
    for (int i = S::n_q; i < S::n_state; ++i) x[i] = std::uniform_real_distribution<double>(-2, 2)(rng);
    jacobian_matrix<S> J;
    CHECK_FALSE(detail::jacobian_loops(sp, 0.4, x, J));
    CHECK((jacobian(sp, 0.4, x) - jacobian_dual(sp, 0.4, x)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("the loop laws hold at random closed states of the four-bar, slider-crank, parallelogram and RSUR loop") {
  // Accelerations against the dense [M Gᵀ; G 0] solve, G·v̇ = −Ġ·v, the
  // power balance and the recovered residual (loop_laws.hpp); measured at
  // round-off (≤ 6e-14), bounded by the solve's accuracy at regular positions.
  std::mt19937 rng(52);
  test::loop_law_errors e;
  models::fourbar_params p;
  test::check_loop_laws(models::fourbar(p), rng, e);
  test::check_loop_laws(models::slider_crank(models::slider_crank_params{}), rng, e);
  p.ground = p.coupler = 1.0;
  p.crank = p.rocker = 0.3;
  test::check_loop_laws(models::fourbar(p), rng, e);
  test::check_loop_laws(invariant_scenes::rsur_closed().scene, rng, e);
  CHECK(e.checked == 40);
  CHECK(e.algorithms < 1e-10);
  CHECK(e.accelerations < 1e-10);
  CHECK(e.power < 1e-10);
  CHECK(e.residual < 1e-12);
}
