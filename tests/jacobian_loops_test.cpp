// The Jacobian of a scene with loops by implicit differentiation
// (simulate/jacobian.hpp, jacobian_loops): where the analytic passes take
// the loop's tree (loops_take_passes), M⁻¹·∂F comes from them and the
// loops' rows are differentiated through the tree's motions
// (dynamics/loop_derivatives.hpp); else inverse dynamics and the loops'
// kinematics run in dual numbers. Either way it is held to jacobian_dual(), which carries
// the dual numbers through the mass matrix, its factor and the loop solve:
// the same derivative by another algorithm, to the solves' round-off (1e-12
// of the largest entry); and to central differences, to theirs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>

#include "loop_links.hpp"
#include "random_params.hpp"
#include "tree_laws.hpp"

using namespace flange;
using test::bar_to;

namespace {

/// A spatial four-bar (as in loop_cut_kinds_test.cpp): the crank turns about
/// z at the origin (r1, driven by a torque of time), out to A = (0.4, 0, 0);
/// joint "j" joins it to the coupler, which reaches B = (0.4, 0.8, 0.3);
/// the rocker turns about y at C = (0.9, 0.8, 0.3) (r2, held by a PD law
/// toward 0.2 rad that also reads r1) and reaches B, where a Spherical "s"
/// joins coupler and rocker. A force of the World pushes the coupler's far
/// end. Of "j" and "s", the one written last is cut.
template <class First, class Second>
auto driven_four_bar(const First& first, const Second& second) {
  auto drive = [](auto t) {
    using std::sin;
    return 0.8 * sin(2.0 * t);
  };
  auto pd = [](auto t, const auto& x) { return -5.0 * (q<"r2">(x) - 0.2) - 0.6 * v<"r2">(x) + 0.3 * v<"r1">(x) + 0 * t; };
  return scene(World<"world">{}, revolute<"r1", axis::z>(drive), bar_to<"crank">({0.4, 0, 0}),
               bar_to<"coupler">({0, 0.8, 0.3}), FixedTranslation<"ground">({.d = {0.9, 0.8, 0.3}}),
               revolute<"r2", axis::y>(pd), bar_to<"rocker">({-0.5, 0, 0}),
               WorldForce<"push">({.value = Vec3d(1.5, -2.0, 0.7)}), first, second,
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "j.frame_a">, connect<"j.frame_b", "coupler.frame_a">,
               connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "r2.frame_a">,
               connect<"r2.frame_b", "rocker.frame_a">, connect<"coupler.frame_b", "s.frame_a">,
               connect<"rocker.frame_b", "s.frame_b">, connect<"coupler.frame_b", "push.frame_b">);
}

/// jacobian_loops() (its route the one the scene takes) against
/// jacobian_dual() and, at 1e-6 of the largest entry, central differences;
/// jacobian() takes it. Driven: the drive of time moves the mechanism.
template <class S, class X>
void check_implicit(const S& scene, double t, const X& x, bool driven = true) {
  jacobian_matrix<S> J;
  Eigen::Matrix<double, S::n_state, 1> ft, ft_d;
  test::poison_stack();
  REQUIRE(detail::jacobian_loops(scene, t, x, J, &ft));
  test::poison_stack();
  const auto Jd = jacobian_dual(scene, t, x, &ft_d);
  const double scale = std::max(1.0, Jd.cwiseAbs().maxCoeff());
  INFO("largest entry " << scale);
  CHECK((J - Jd).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((ft - ft_d).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  if (driven) CHECK(ft.template tail<S::n_v>().cwiseAbs().maxCoeff() > 0.1);
  CHECK((J - jacobian_finite_difference(scene, t, x)).cwiseAbs().maxCoeff() <= 1e-6 * scale);
  CHECK((jacobian(scene, t, x) - J).cwiseAbs().maxCoeff() == 0.0);
}

/// States on the loop of scene s (r1 at angle th turning at w, closed from
/// there) and off it by up to 1e-3 in every coordinate.
template <class S>
void check_states(const S& s, std::mt19937& rng) {
  for (int k = 0; k < 3; ++k) {
    auto x = neutral_state(s);
    set_joint<"r1">(s, x, {.q = test::uniform(rng, -0.1, 0.1), .v = test::uniform(rng, -2, 2)});
    close_loops<"r1">(s, x);
    check_implicit(s, 0.4, x);
    for (int i = 0; i < S::n_q; ++i) x[i] += test::uniform(rng, -1e-3, 1e-3);
    normalize(s, x);
    for (int i = S::n_q; i < S::n_state; ++i) x[i] += test::uniform(rng, -0.5, 0.5);
    check_implicit(s, 0.4, x);
  }
}

}  // namespace

TEST_CASE("a loop whose tree the analytic passes take: drives, a PD law and a force, as dual numbers give them") {
  std::mt19937 rng(11);
  const auto cut_s = driven_four_bar(Universal<"j">({.n_a = {0, 0, 1}, .n_b = {1, 0, 0}}), Spherical<"s">{});
  using S = decltype(cut_s);
  STATIC_REQUIRE(detail::loops_take_passes<S>());
  STATIC_REQUIRE(constraint_count<S> == 3);
  check_states(cut_s, rng);
  // The planar four-bar of the benchmarks takes them too, and with a
  // spring-damper in its cut joint (the cut joint's own force, which the
  // loop passes on as a load on its two links).
  STATIC_REQUIRE(detail::loops_take_passes<std::remove_cvref_t<decltype(models::fourbar(models::fourbar_params{}))>>());
  const models::fourbar_params p{};
  const auto sprung = scene(
      World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, models::bar<"crank">(p.crank, p.m_crank),
      Revolute<"crank_pin", axis::z>{}, models::bar<"coupler">(p.coupler, p.m_coupler), Revolute<"rocker_pin", axis::z>{},
      models::bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
      Revolute<"rocker_pivot", axis::z, axis_law::spring_damper>({.c = 30, .d = 2, .phi0 = 0.3}),
      connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
      connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
      connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
      connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "rocker_pivot.frame_a">,
      connect<"rocker.frame_b", "rocker_pivot.frame_b">);
  STATIC_REQUIRE(detail::loops_take_passes<std::remove_cvref_t<decltype(sprung)>>());
  for (const double th : {0.4, 1.0, 2.2}) {
    const auto q = models::fourbar_coordinates(p, th, models::freudenstein_rocker(p, th));
    std::array<double, 6> x{q[0], q[1], q[2], test::uniform(rng, -3, 3), 0, 0};
    close_loops<"crank_pivot">(sprung, x);
    check_implicit(sprung, 0.4, x, false);  // nothing here reads the time
  }
}

TEST_CASE("a cut with a row on the turn between its frames, on the passes: as dual numbers give it") {
  // Cut at a Universal: three rows on B's position and one on the angle
  // between its axes, whose ∂(Ġ·v)/∂v = 2·Ġ holds as for the others (every
  // row is the rate of a function of q). With "j" a Universal too the
  // loop's four rates meet four rows: it closes at q = 0 alone and cannot
  // move (its drive moves nothing), and G·v ≠ 0 there for the rates given,
  // the loop's velocity off its own; the Jacobian is the same implicit one.
  // (Off q = 0 the loop solve damps a row, and jacobian() takes dual
  // numbers.)
  std::mt19937 rng(13);
  const auto rows = driven_four_bar(Universal<"j">({.n_a = {0, 0, 1}, .n_b = {1, 0, 0}}),
                                    Universal<"s">({.n_a = {0, 1, 0}, .n_b = {0, 0, 1}}));
  using S = decltype(rows);
  STATIC_REQUIRE(detail::loops_take_passes<S>());
  STATIC_REQUIRE(constraint_count<S> == 4);
  for (int k = 0; k < 4; ++k) {
    auto x = neutral_state(rows);
    for (int i = S::n_q; i < S::n_state; ++i) x[i] = test::uniform(rng, -1, 1);
    check_implicit(rows, 0.4, x, false);
  }
}

TEST_CASE("a loop whose tree holds a ball: inverse dynamics in dual numbers, as dual numbers give it") {
  // An RSSR loop: "j" a Spherical too, in the tree (the coupler free to spin
  // about its own line: two degrees of freedom).
  std::mt19937 rng(12);
  const auto ball = driven_four_bar(Spherical<"j">{}, Spherical<"s">{});
  using S = decltype(ball);
  STATIC_REQUIRE_FALSE(detail::loops_take_passes<S>());  // j's quaternion moves with all three of its rates
  STATIC_REQUIRE(constraint_count<S> == 3);
  check_states(ball, rng);
}

TEST_CASE("loops in the plane through a prismatic joint and loops that share links, on the passes: as dual numbers give them") {
  // The slider-crank of models/linkages.hpp (its slider a Prismatic in the
  // loop's tree) and a row of two parallelogram windows (two loops, the
  // middle post in both), each on its loop and off it.
  std::mt19937 rng(17);
  auto wobble = [&](const auto& s, auto x) {
    using S = std::remove_cvref_t<decltype(s)>;
    for (int i = 0; i < S::n_q; ++i) x[i] += test::uniform(rng, -1e-3, 1e-3);
    for (int i = S::n_q; i < S::n_state; ++i) x[i] += test::uniform(rng, -0.5, 0.5);
    return x;
  };
  const auto sc = models::slider_crank(models::slider_crank_params{});
  STATIC_REQUIRE(detail::loops_take_passes<std::remove_cvref_t<decltype(sc)>>());
  for (const double th : {0.3, 1.0, 2.5}) {
    std::array<double, 6> x{th, 0.2, 0.35, test::uniform(rng, -3, 3), 0.5, -0.3};
    close_loops<"crank_pivot">(sc, x);
    check_implicit(sc, 0.4, x, false);
    check_implicit(sc, 0.4, wobble(sc, x), false);
  }
  const auto row = models::window_row<2>(models::window_row_params{});
  using R = std::remove_cvref_t<decltype(row)>;
  STATIC_REQUIRE(detail::loops_take_passes<R>());
  STATIC_REQUIRE(constraint_count<R> == 4);
  for (const double a : {0.6, 1.2}) {
    typename R::state_type x{};
    for (int i = 0; i <= 2; ++i) {
      const int k = R::q_offset("post_pivot" + std::to_string(i));
      x[k] = a;
      x[R::n_q + k] = test::uniform(rng, -1, 1);
    }
    for (int i = 0; i < 2; ++i) {
      const int k = R::q_offset("top_pin" + std::to_string(i));
      x[k] = -a;
      x[R::n_q + k] = -x[R::n_q + R::q_offset("post_pivot" + std::to_string(i))];
    }
    close_loops<"post_pivot0">(row, x);
    check_implicit(row, 0.4, x, false);
    check_implicit(row, 0.4, wobble(row, x), false);
  }
}
