// Every joint kind can close a loop: a loop cut at a Universal, a
// Cylindrical, a Planar joint or a FreeMotion moves as the same mechanism
// cut at another of its joints (its rows, dynamics/loops.hpp: 4, 4, 3 and
// none). Each mechanism is written twice, the joint to cut written last, and
// the two runs are held to each other; the cut joint's coordinates, as
// recover gives them (its cut_state), to the same joint's state in the other
// run; and each run to its own energy and closure.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

#include "loop_laws.hpp"
#include "loop_links.hpp"

using namespace flange;

namespace {

using test::bar_to;

/// A spatial four-bar, closed at q = 0: the crank turns about z at the
/// origin (r1) out to A = (0.4, 0, 0); the coupler runs from A to
/// B = (0.4, 0.8, 0.3); the rocker turns about y at C = (0.9, 0.8, 0.3)
/// (r2) and reaches B. Joint "j" joins crank and coupler at A, a Spherical
/// "s" joins coupler and rocker at B; of the two, the one written last
/// (first, second) is cut.
template <class First, class Second>
auto four_bar(const First& first, const Second& second) {
  return scene(World<"world">{}, Revolute<"r1", axis::z>{}, bar_to<"crank">({0.4, 0, 0}),
               bar_to<"coupler">({0, 0.8, 0.3}), FixedTranslation<"ground">({.d = {0.9, 0.8, 0.3}}),
               Revolute<"r2", axis::y>{}, bar_to<"rocker">({-0.5, 0, 0}), first, second,
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "j.frame_a">, connect<"j.frame_b", "coupler.frame_a">,
               connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "r2.frame_a">,
               connect<"r2.frame_b", "rocker.frame_a">, connect<"coupler.frame_b", "s.frame_a">,
               connect<"rocker.frame_b", "s.frame_b">);
}

/// A crank and a coupler whose far end B = (0.4, 0.8, 0.3) moves on a
/// slider: a Planar joint "j" (frame_a on the slider) keeps B in the
/// slider's plane normal to x and lets the coupler turn only about x; the
/// slider moves along x (Prismatic "p" at B on the World). A Spherical "s"
/// joins crank and coupler at A = (0.4, 0, 0). Two degrees of freedom. Of
/// "j" and "s", the one written last is cut.
template <class First, class Second>
auto planar_slider(const First& first, const Second& second) {
  return scene(World<"world">{}, Revolute<"r1", axis::z>{}, bar_to<"crank">({0.4, 0, 0}),
               bar_to<"coupler">({0, 0.8, 0.3}), FixedTranslation<"ground">({.d = {0.4, 0.8, 0.3}}),
               Prismatic<"p", axis::x>{}, Body<"slider">({.m = 0.5, .J = Mat3d::Identity() * 0.01}), first, second,
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "crank.frame_a">,
               connect<"crank.frame_b", "s.frame_a">, connect<"s.frame_b", "coupler.frame_a">,
               connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "p.frame_a">,
               connect<"p.frame_b", "slider.frame_a">, connect<"slider.frame_a", "j.frame_a">,
               connect<"j.frame_b", "coupler.frame_b">);
}

/// A pendulum on r1 (about z at the origin) whose bar is also tied to the
/// World by a FreeMotion "j", frame_a on the World: cut at "j", the loop has
/// no constraint; cut at r1, five rows hold the free bar to the pivot.
template <class First, class Second>
auto free_pendulum(const First& first, const Second& second) {
  return scene(World<"world">{}, bar_to<"bar">({0.6, 0, 0}), first, second,
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "bar.frame_a">,
               connect<"world.frame_b", "j.frame_a">, connect<"j.frame_b", "bar.frame_a">);
}

/// How far apart two angles are, as turns: a cut joint's angle comes from
/// its frames, within (−π, π].
double angle_gap(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * std::numbers::pi));
}

/// The largest energy change (relative) and loop residual along a run.
template <class S, class Tr>
std::pair<double, double> drift(const S& s, const Tr& tr) {
  const double E0 = recover(s, tr.t[0], tr.x[0]).energy();
  double dE = 0, phi = 0;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    dE = std::max(dE, std::abs(recover(s, tr.t[k], tr.x[k]).energy() - E0) / std::abs(E0));
    if constexpr (constraint_count<S> > 0) phi = std::max(phi, loop_residual(s, tr.x[k]).max_phi());
  }
  return {dE, phi};
}

/// Runs a mechanism from q = 0 with r1 turning at w rad/s (the loop closed
/// from there), tolerance 1e-12.
template <class S>
auto run(const S& s, double w = 2.0) {
  auto x = neutral_state(s);
  set_joint<"r1">(s, x, {.q = 0.0, .v = w});
  close_loops<"r1">(s, x);
  return simulate(s, x, output_times(0.0, 1.5, 0.05), {.tolerance = 1e-12});
}

/// Each run's energy kept and loop closed; r1's angle in run a against run b
/// (the largest difference), and that it swings.
template <class A, class B, class TA, class TB, class R1A, class R1B>
double compare_runs(const A& a, const TA& ta, const B& b, const TB& tb, R1A&& r1a, R1B&& r1b) {
  const auto [dEa, phia] = drift(a, ta);
  const auto [dEb, phib] = drift(b, tb);
  CHECK(dEa < 1e-8);
  CHECK(dEb < 1e-8);
  CHECK(phia < 1e-10);
  CHECK(phib < 1e-10);
  REQUIRE(ta.size() == tb.size());
  double worst = 0, swing = 0;
  for (std::size_t k = 0; k < ta.size(); ++k) {
    const double qa = r1a(k), qb = r1b(k);  // the same angle, or 2π apart
    worst = std::max(worst, angle_gap(qa, qb));
    swing = std::max(swing, std::abs(qa));
  }
  CHECK(swing > 0.3);  // the mechanism moves
  return worst;
}

}  // namespace

TEST_CASE("A loop cut at a Universal moves as the loop cut at a Spherical") {
  const auto u = Universal<"j">({.n_a = {0, 0, 1}, .n_b = {1, 0, 0}});
  const auto cut_u = four_bar(Spherical<"s">{}, u);
  const auto cut_s = four_bar(u, Spherical<"s">{});
  using U = decltype(cut_u);
  using S = decltype(cut_s);
  STATIC_REQUIRE(cut_joints<U>()[0] == "j");
  STATIC_REQUIRE(cut_joints<S>()[0] == "s");
  STATIC_REQUIRE(constraint_count<U> == 4);
  STATIC_REQUIRE(constraint_count<S> == 3);
  const auto tu = run(cut_u);
  const auto ts = run(cut_s);
  const double worst = compare_runs(
      cut_u, tu, cut_s, ts, [&](std::size_t k) { return get_joint<"r1">(cut_u, tu.x[k]).q; },
      [&](std::size_t k) { return get_joint<"r1">(cut_s, ts.x[k]).q; });
  CHECK(worst < 1e-10);
  // The cut Universal's angles, from its frames, against its state when s is cut.
  double e = 0;
  for (std::size_t k = 0; k < tu.size(); ++k) {
    const auto sol = recover(cut_u, tu.t[k], tu.x[k]);
    const auto j = get_joint<"j">(cut_s, ts.x[k]);
    e = std::max({e, angle_gap(sol.template internal<"j", "phi1">(), j.q[0]),
                  angle_gap(sol.template internal<"j", "phi2">(), j.q[1])});
  }
  CHECK(e < 1e-10);
}

TEST_CASE("A loop cut at a Cylindrical moves as the loop cut at a Spherical") {
  const auto c = Cylindrical<"j">({.n = {1, 0, 0}});
  const auto cut_c = four_bar(Spherical<"s">{}, c);
  const auto cut_s = four_bar(c, Spherical<"s">{});
  using C = decltype(cut_c);
  STATIC_REQUIRE(cut_joints<C>()[0] == "j");
  STATIC_REQUIRE(cut_joints<decltype(cut_s)>()[0] == "s");
  STATIC_REQUIRE(constraint_count<C> == 4);
  const auto tc = run(cut_c);
  const auto ts = run(cut_s);
  const double worst = compare_runs(
      cut_c, tc, cut_s, ts, [&](std::size_t k) { return get_joint<"r1">(cut_c, tc.x[k]).q; },
      [&](std::size_t k) { return get_joint<"r1">(cut_s, ts.x[k]).q; });
  CHECK(worst < 1e-10);
  double e = 0, slide = 0;
  for (std::size_t k = 0; k < tc.size(); ++k) {
    const auto sol = recover(cut_c, tc.t[k], tc.x[k]);
    const auto j = get_joint<"j">(cut_s, ts.x[k]);
    e = std::max({e, std::abs(sol.template internal<"j", "s">() - j.q[0]),
                  angle_gap(sol.template internal<"j", "phi">(), j.q[1]),
                  std::abs(sol.template internal_rate<"j", "s">() - j.v[0]),
                  std::abs(sol.template internal_rate<"j", "phi">() - j.v[1])});
    slide = std::max(slide, std::abs(j.q[0]));
  }
  CHECK(e < 1e-10);
  CHECK(slide > 0.01);  // it slides as well as turns
}

TEST_CASE("A loop cut at a Planar joint moves as the loop cut at a Spherical") {
  const auto p = Planar<"j">({.n = {1, 0, 0}, .n_x = {0, 1, 0}});
  const auto cut_p = planar_slider(Spherical<"s">{}, p);
  const auto cut_s = planar_slider(p, Spherical<"s">{});
  using P = decltype(cut_p);
  STATIC_REQUIRE(cut_joints<P>()[0] == "j");
  STATIC_REQUIRE(cut_joints<decltype(cut_s)>()[0] == "s");
  STATIC_REQUIRE(constraint_count<P> == 3);
  // From rest: with two degrees of freedom, rates held at r1 alone would be
  // completed by each cut's own least change, not the same motion.
  const auto tp = run(cut_p, 0.0);
  const auto ts = run(cut_s, 0.0);
  const double worst = compare_runs(
      cut_p, tp, cut_s, ts, [&](std::size_t k) { return get_joint<"r1">(cut_p, tp.x[k]).q; },
      [&](std::size_t k) { return get_joint<"r1">(cut_s, ts.x[k]).q; });
  CHECK(worst < 1e-10);
  double e = 0;
  for (std::size_t k = 0; k < tp.size(); ++k) {
    const auto sol = recover(cut_p, tp.t[k], tp.x[k]);
    const auto j = get_joint<"j">(cut_s, ts.x[k]);
    e = std::max({e, std::abs(sol.template internal<"j", "s_x">() - j.q[0]),
                  std::abs(sol.template internal<"j", "s_y">() - j.q[1]),
                  angle_gap(sol.template internal<"j", "phi">(), j.q[2]),
                  std::abs(sol.template internal_rate<"j", "s_x">() - j.v[0]),
                  std::abs(sol.template internal_rate<"j", "s_y">() - j.v[1]),
                  std::abs(sol.template internal_rate<"j", "phi">() - j.v[2])});
  }
  CHECK(e < 1e-10);
}

TEST_CASE("A loop cut at a FreeMotion has no constraint and moves as the loop cut at its revolute") {
  const auto cut_f = free_pendulum(Revolute<"r1", axis::z>{}, FreeMotion<"j">{});
  const auto cut_r = free_pendulum(FreeMotion<"j">{}, Revolute<"r1", axis::z>{});
  using F = decltype(cut_f);
  using R = decltype(cut_r);
  STATIC_REQUIRE(cut_joints<F>()[0] == "j");
  STATIC_REQUIRE(cut_joints<R>()[0] == "r1");
  STATIC_REQUIRE(constraint_count<F> == 0);
  STATIC_REQUIRE(constraint_count<R> == 5);
  const auto tf = run(cut_f);
  auto x = neutral_state(cut_r);
  set_joint<"j">(cut_r, x, {.w = {0, 0, 2}});
  close_loops<"j">(cut_r, x);
  const auto tr = simulate(cut_r, x, output_times(0.0, 1.5, 0.05), {.tolerance = 1e-12});
  const double worst = compare_runs(
      cut_f, tf, cut_r, tr, [&](std::size_t k) { return get_joint<"r1">(cut_f, tf.x[k]).q; },
      [&](std::size_t k) { return recover(cut_r, tr.t[k], tr.x[k]).template internal<"r1", "phi">(); });
  CHECK(worst < 1e-10);
  double e = 0;
  for (std::size_t k = 0; k < tf.size(); ++k) {
    const auto sol = recover(cut_f, tf.t[k], tf.x[k]);
    const auto j = get_joint<"j">(cut_r, tr.x[k]);
    e = std::max({e, (sol.template internal<"j", "r_rel">() - j.r).norm(),
                  (sol.template internal<"j", "R_rel">() - j.R.R).norm(),
                  (sol.template internal_rate<"j", "r_rel">() - j.v).norm()});
  }
  CHECK(e < 1e-10);
}

TEST_CASE("A cut joint is read, set and held by name as a tree joint is") {
  // The Cylindrical four-bar cut at j and, for the reference, cut at s
  // (j then a joint of the tree, its state in x).
  const auto c = Cylindrical<"j">({.n = {1, 0, 0}});
  const auto cut_c = four_bar(Spherical<"s">{}, c);
  const auto cut_s = four_bar(c, Spherical<"s">{});
  const auto tc = run(cut_c);
  const auto ts = run(cut_s);
  double read = 0, set = 0;
  for (std::size_t k = 5; k < tc.size(); k += 10) {
    // get_joint of the cut joint: its frames' reading, as the tree's state.
    const auto jc = get_joint<"j">(cut_c, tc.x[k]);
    const auto js = get_joint<"j">(cut_s, ts.x[k]);
    for (int i = 0; i < 2; ++i) read = std::max({read, std::abs(jc.q[i] - js.q[i]), std::abs(jc.v[i] - js.v[i])});
    // initial_state naming the cut joint closes the loop holding it there:
    // the same position and motion as the reference run's at that time.
    const auto x = initial_state<"j">(cut_c, {.q = js.q, .v = js.v});
    for (const auto& [a, b] : {std::pair{get_joint<"r1">(cut_c, x), get_joint<"r1">(cut_s, ts.x[k])},
                               std::pair{get_joint<"r2">(cut_c, x), get_joint<"r2">(cut_s, ts.x[k])}})
      set = std::max({set, angle_gap(a.q, b.q), std::abs(a.v - b.v)});
  }
  CHECK(read < 1e-10);
  CHECK(set < 1e-10);
  // close_loops holding a cut joint, on the planar four-bar cut at its
  // rocker pivot (one coordinate, one degree of freedom): from a state
  // opened by turning the crank, it closes with the rocker pivot where the
  // open state's frames place it; closing without the hold moves it (so
  // the check can tell).
  const models::fourbar_params fp{};
  const auto fb = models::fourbar(fp);
  STATIC_REQUIRE(cut_joints<decltype(fb)>()[0] == "rocker_pivot");
  const auto q0 = models::fourbar_coordinates(fp, 1.0, models::freudenstein_rocker(fp, 1.0));
  std::array<double, 6> y{q0[0], q0[1], q0[2], 2.0, 0, 0};
  close_loops<"crank_pivot">(fb, y);
  y[fb.q_offset<"crank_pivot">()] += 0.05;
  const auto target = get_joint<"rocker_pivot">(fb, y);
  auto z = y;
  close_loops<"rocker_pivot">(fb, y);
  close_loops<>(fb, z);
  const auto held = get_joint<"rocker_pivot">(fb, y), unheld = get_joint<"rocker_pivot">(fb, z);
  CHECK(std::abs(held.q - target.q) < 1e-10);
  CHECK(std::abs(held.v - target.v) < 1e-10);
  CHECK(loop_residual(fb, y).max_phi() < 1e-10);
  CHECK(std::abs(unheld.q - target.q) > 1e-3);
  // A slide the coupler cannot reach while the loop closes.
  CHECK_THROWS_WITH((initial_state<"j">(cut_c, {.q = {3.0, 0.0}})),
                    Catch::Contains("cut joints held (\"j\") cannot be placed as asked"));
}

TEST_CASE("the loop laws hold on loops cut at a Universal, a Cylindrical, a Planar joint and a Spherical") {
  std::mt19937 rng(52);
  test::loop_law_errors e;
  const auto u = Universal<"j">({.n_a = {0, 0, 1}, .n_b = {1, 0, 0}});
  const auto c = Cylindrical<"j">({.n = {1, 0, 0}});
  const auto p = Planar<"j">({.n = {1, 0, 0}, .n_x = {0, 1, 0}});
  test::check_loop_laws(four_bar(Spherical<"s">{}, u), rng, e);
  test::check_loop_laws(four_bar(Spherical<"s">{}, c), rng, e);
  test::check_loop_laws(four_bar(u, Spherical<"s">{}), rng, e);
  test::check_loop_laws(planar_slider(Spherical<"s">{}, p), rng, e);
  test::check_loop_laws(planar_slider(p, Spherical<"s">{}), rng, e);
  CHECK(e.checked == 50);
  CHECK(e.algorithms < 1e-10);
  CHECK(e.accelerations < 1e-10);
  CHECK(e.power < 1e-10);
  CHECK(e.residual < 1e-12);
}
