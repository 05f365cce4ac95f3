// Loops whose constraints repeat each other: Bricard's orthogonal linkage,
// six revolutes whose five cut rows on five rates leave, by count, no
// motion, and by geometry one; a planar loop written with run-time axes;
// a parallelogram with a third, redundant leg. The rows that repeat others are found and
// left out of the solve (constraint_redundancy, dynamics/loop_solve.hpp).
// Checked against its kinematic symmetry, the conservation of energy, and
// the same linkage made non-redundant by a massless seventh revolute.
#include <boost/numeric/odeint.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string_view>

#include <flange/flange.hpp>

#include "loop_laws.hpp"
#include "loop_links.hpp"
#include <flange/models/linkages.hpp>

using namespace flange;

namespace {

using test::bar_to;

/// The orthogonal Bricard linkage along six edges of a unit cube: joint
/// axes y, z, x, y, z, x, each bar along the common normal of its two axes,
/// the World the sixth bar. With Extra, a massless revolute j7 about a
/// generic axis between b5 and j6: seven joints, one motion by count.
template <bool Extra>
auto bricard() {
  const auto parts = [](auto... extra) {
    return scene(World<"world">{}, Revolute<"j1", axis::y>{}, bar_to<"b1">({1, 0, 0}), Revolute<"j2", axis::z>{},
                 bar_to<"b2">({0, 1, 0}), Revolute<"j3", axis::x>{}, bar_to<"b3">({0, 0, 1}), Revolute<"j4", axis::y>{},
                 bar_to<"b4">({-1, 0, 0}), Revolute<"j5", axis::z>{}, bar_to<"b5">({0, -1, 0}),
                 FixedTranslation<"ground">({.d = {0, 0, 1}}), Revolute<"j6", axis::x>{}, extra...,
                 connect<"world.frame_b", "j1.frame_a">, connect<"j1.frame_b", "b1.frame_a">,
                 connect<"b1.frame_b", "j2.frame_a">, connect<"j2.frame_b", "b2.frame_a">,
                 connect<"b2.frame_b", "j3.frame_a">, connect<"j3.frame_b", "b3.frame_a">,
                 connect<"b3.frame_b", "j4.frame_a">, connect<"j4.frame_b", "b4.frame_a">,
                 connect<"b4.frame_b", "j5.frame_a">, connect<"j5.frame_b", "b5.frame_a">,
                 connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "j6.frame_b">);
  };
  if constexpr (Extra)
    return parts(Revolute<"j7">({.n = {0.3, 0.5, 0.8}}), connect<"b5.frame_b", "j7.frame_a">,
                 connect<"j7.frame_b", "j6.frame_a">);
  else return parts(connect<"b5.frame_b", "j6.frame_a">);
}

}  // namespace

TEST_CASE("Bricard's linkage: 5 rows on 5 rates, one of them redundant") {
  using S = decltype(bricard<false>());
  STATIC_REQUIRE(cut_joints<S>()[0] == "j6");
  STATIC_REQUIRE(constraint_count<S> == 5);
  STATIC_REQUIRE(S::n_v == 5);
  const auto s = bricard<false>();
  auto x = initial_state<"j1">(s, {.q = 0.0, .v = 1.0});
  close_loops<"j1">(s, x);
  const auto r = loop_rank(s, x);
  CHECK(r.rows == 5);
  CHECK(r.rank == 4);
  CHECK(r.dof == 1);
  // With the seventh joint, 5 independent rows on 6 rates: one motion too.
  const auto s7 = bricard<true>();
  auto x7 = initial_state<"j2">(s7, {.q = 0.0, .v = 1.0});
  close_loops<"j2">(s7, x7);
  const auto r7 = loop_rank(s7, x7);
  CHECK(r7.rows == 5);
  CHECK(r7.rank == 5);
  CHECK(r7.dof == 1);
}

namespace {
/// Each run's largest departure from the linkage's symmetry: on its one
/// motion the joints keep φ3 = φ5 = −φ1 and φ4 = −φ2 (a property of the
/// configuration curve, not of the dynamics).
template <class Tr>
double symmetry_error(const Tr& tr) {
  double e = 0;
  for (const auto& x : tr.x)
    e = std::max({e, std::abs(x[0] + x[2]), std::abs(x[0] + x[4]), std::abs(x[1] + x[3])});
  return e;
}
}  // namespace

TEST_CASE("Bricard's linkage swings with its energy kept and its loop closed") {
  const auto s = bricard<false>();
  auto x = initial_state<"j1">(s, {.q = 0.0, .v = 1.0});
  close_loops<"j1">(s, x);
  const auto times = output_times(0.0, 3.0, 0.05);
  const auto tr = simulate(s, x, times, {.tolerance = 1e-12});
  const double E0 = recover(s, 0.0, x).energy();
  double dE = 0, phi = 0, phid = 0, swing = 0;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    dE = std::max(dE, std::abs(recover(s, tr.t[k], tr.x[k]).energy() - E0) / E0);
    const auto r = loop_residual(s, tr.x[k]);
    phi = std::max(phi, r.max_phi());
    phid = std::max(phid, r.max_phid());
    swing = std::max(swing, std::abs(tr.x[k][0]));
  }
  CHECK(dE < 1e-8);
  CHECK(phi < 1e-10);
  CHECK(phid < 1e-10);
  CHECK(symmetry_error(tr) < 1e-9);
  CHECK(swing > 3);  // j1 swings out to 0.43 rad, back, and over (3.4 rad at 3 s)
  // Steps of a smooth one-degree-of-freedom motion: the redundant row kept
  // in the solve took about 2.3 million steps a second at this tolerance.
  CHECK(tr.steps < 1000);

  SECTION("at the default tolerance, the error is the stepper's") {
    const auto loose = simulate(s, x, times);
    double worst = 0;
    for (std::size_t k = 0; k < tr.size(); ++k)
      for (int i = 0; i < 5; ++i) worst = std::max(worst, std::abs(loose.x[k][i] - tr.x[k][i]));
    CHECK(worst < 1e-6);
    CHECK(loose.steps < 200);
  }
}

TEST_CASE("Bricard's linkage moves as the same linkage made non-redundant by a massless seventh revolute") {
  const auto s6 = bricard<false>();
  const auto s7 = bricard<true>();
  using S7 = decltype(s7);
  // j7, written last, would be cut and leave j6 turning nothing with mass;
  // j5 is the last-written joint whose cut leaves mass beyond every joint.
  STATIC_REQUIRE(cut_joints<S7>()[0] == "j5");
  STATIC_REQUIRE(S7::n_v == 6);
  auto x6 = initial_state<"j1">(s6, {.q = 0.0, .v = 1.0});
  close_loops<"j1">(s6, x6);
  // The same start: every angle 0, j2's rate as s6 found it.
  auto x7 = initial_state<"j2">(s7, {.q = 0.0, .v = x6[5 + 1]});
  close_loops<"j2">(s7, x7);
  // Until 2 s: near 2.4 s the linkage passes close to a position where the
  // seven-joint loop's own constraints lose rank, and its damped solve
  // loses the energy's digits there, which the six-joint linkage keeps to
  // 1e-10 (docs/loops.md, "Redundant constraints").
  const auto times = output_times(0.0, 2.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  const auto t6 = simulate(s6, x6, times, o);
  const auto t7 = simulate(s7, x7, times, o);
  double gap = 0, j7 = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const auto r6 = recover(s6, t6.t[k], t6.x[k]);
    const auto r7 = recover(s7, t7.t[k], t7.x[k]);
    for (const std::string_view f : {"b1.frame_b", "b2.frame_b", "b3.frame_b", "b4.frame_b"})
      gap = std::max(gap, (r6.frame(f).r - r7.frame(f).r).norm());
    j7 = std::max(j7, std::abs(r7.internal<"j7", "phi">()));
  }
  CHECK(gap < 1e-9);
  CHECK(j7 < 1e-9);  // the seventh joint stays where it was put
}

TEST_CASE("a planar four-bar written with run-time axes moves as the one with axis::z") {
  const models::fourbar_params p;
  const auto typed = models::fourbar(p);
  const auto any = models::fourbar<axis::any>(p);  // every axis {0, 0, 1} at run time: a spatial loop
  using S = decltype(any);
  STATIC_REQUIRE(constraint_count<S> == 5);  // a spatial revolute's cut, on 3 rates
  STATIC_REQUIRE(S::n_v == 3);
  const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  std::array<double, 6> x{q[0], q[1], q[2], 2.0, 0, 0};
  close_loops<"crank_pivot">(typed, x);
  auto y = x;
  close_loops<"crank_pivot">(any, y);
  const auto r = loop_rank(any, y);
  CHECK(r.rank == 2);  // the 3 out-of-plane rows repeat what the tree's axes already fix
  CHECK(r.dof == 1);
  const auto times = output_times(0.0, 5.0, 0.1);
  const simulate_options o{.tolerance = 1e-12};
  const auto a = simulate(typed, x, times, o);
  const auto b = simulate(any, y, times, o);
  double worst = 0;
  for (std::size_t k = 0; k < times.size(); ++k)
    for (int i = 0; i < 6; ++i) worst = std::max(worst, std::abs(a.x[k][i] - b.x[k][i]));
  CHECK(worst < 1e-10);
}

namespace {
/// Three equal cranks (length L, pivots d apart on the ground) carrying one
/// coupler, planar about z: a parallelogram with a third leg. By count
/// (two loops, 4 rows on 4 rates) it cannot move; by geometry it swings,
/// the coupler translating. The coupler is two bars, the middle crank's pin
/// at their joint.
struct triple_crank_params {
  double L = 0.5, d = 0.4, m_crank = 1.0, m_half = 1.5;
};
auto triple_crank(const triple_crank_params& p) {
  using models::bar;
  return scene(World<"world">{}, Revolute<"p1", axis::z>{}, bar<"c1">(p.L, p.m_crank), Revolute<"t1", axis::z>{},
               bar<"left">(p.d, p.m_half), bar<"right">(p.d, p.m_half),
               FixedTranslation<"g2">({.d = Vec3d(p.d, 0, 0)}), Revolute<"p2", axis::z>{}, bar<"c2">(p.L, p.m_crank),
               Revolute<"t2", axis::z>{}, FixedTranslation<"g3">({.d = Vec3d(2 * p.d, 0, 0)}),
               Revolute<"p3", axis::z>{}, bar<"c3">(p.L, p.m_crank), Revolute<"t3", axis::z>{},
               connect<"world.frame_b", "p1.frame_a">, connect<"p1.frame_b", "c1.frame_a">,
               connect<"c1.frame_b", "t1.frame_a">, connect<"t1.frame_b", "left.frame_a">,
               connect<"left.frame_b", "right.frame_a">, connect<"world.frame_b", "g2.frame_a">,
               connect<"g2.frame_b", "p2.frame_a">, connect<"p2.frame_b", "c2.frame_a">,
               connect<"c2.frame_b", "t2.frame_a">, connect<"left.frame_b", "t2.frame_b">,
               connect<"world.frame_b", "g3.frame_a">, connect<"g3.frame_b", "p3.frame_a">,
               connect<"p3.frame_b", "c3.frame_a">, connect<"c3.frame_b", "t3.frame_a">,
               connect<"right.frame_b", "t3.frame_b">);
}
}  // namespace

TEST_CASE("a parallelogram with a redundant third leg swings as its one-coordinate equation of motion") {
  const triple_crank_params p;
  const auto s = triple_crank(p);
  using S = decltype(s);
  STATIC_REQUIRE(constraint_count<S> == 4);
  STATIC_REQUIRE(S::n_v == 4);
  // Hanging down, the cranks 0.6 rad off and still: a swing that stays
  // away from the flat positions, where a parallelogram may fold over.
  const double th0 = -std::numbers::pi / 2 + 0.6;
  auto x = initial_state<"p1", "t1", "p2", "p3">(s, {.q = th0}, {.q = -th0}, {.q = th0}, {.q = th0});
  close_loops<"p1">(s, x);
  const auto r = loop_rank(s, x);
  CHECK(r.rank == 3);
  CHECK(r.dof == 1);
  // Each crank turns about its pivot (I = m·L²/3, models::bar), the coupler
  // (mass 2·m_half) translates with the crank tips:
  //   (3·m·L²/3 + M·L²)·θ̈ = −(3·m·L/2 + M·L)·g·cos θ.
  const double g = 9.81, M = 2 * p.m_half;
  const double inertia = p.m_crank * p.L * p.L + M * p.L * p.L;
  const double moment = (1.5 * p.m_crank * p.L + M * p.L) * g;
  const auto times = output_times(0.0, 3.0, 0.1);
  const auto tr = simulate(s, x, times, {.tolerance = 1e-12});
  // The reference by the same stepper on the one-coordinate equation, far tighter.
  std::array<double, 2> y{th0, 0};
  double worst = 0, lowest = th0;
  auto rhs = [&](const std::array<double, 2>& z, std::array<double, 2>& dz, double) {
    dz[0] = z[1];
    dz[1] = -moment * std::cos(z[0]) / inertia;
  };
  auto stepper = boost::numeric::odeint::make_dense_output(1e-14, 1e-14,
                                                            boost::numeric::odeint::runge_kutta_dopri5<std::array<double, 2>>());
  std::size_t k = 1;
  boost::numeric::odeint::integrate_times(stepper, rhs, y, times.begin(), times.end(), 1e-3,
                                          [&](const std::array<double, 2>& z, double t) {
                                            if (t == 0) return;
                                            worst = std::max(worst, std::abs(tr.x[k][0] - z[0]));
                                            lowest = std::min(lowest, tr.x[k][0]);
                                            ++k;
                                          });
  CHECK(k == times.size());
  CHECK(worst < 1e-9);
  CHECK(lowest < -std::numbers::pi / 2 - 0.5);  // it swung through the bottom
  // The coupler stays level: t1 undoes p1.
  for (const auto& xs : tr.x) CHECK(std::abs(xs[0] + xs[1]) < 1e-10);
}

TEST_CASE("the loop laws hold on the redundant loops: Bricard's linkage, run-time axes, a third leg") {
  // A redundant row kept in the solve shows here: with the redundancy test
  // off, Bricard's linkage broke the power balance by 100 % of its terms.
  std::mt19937 rng(52);
  test::loop_law_errors e;
  test::check_loop_laws(bricard<false>(), rng, e);
  test::check_loop_laws(bricard<true>(), rng, e);
  test::check_loop_laws(models::fourbar<axis::any>(models::fourbar_params{}), rng, e);
  CHECK(e.checked == 30);
  // The third leg's random closed states crowd at its flat positions: the
  // states of a swing instead.
  const auto s = triple_crank(triple_crank_params{});
  const double th0 = -std::numbers::pi / 2 + 0.6;
  auto x = initial_state<"p1", "t1", "p2", "p3">(s, {.q = th0}, {.q = -th0}, {.q = th0}, {.q = th0});
  close_loops<"p1">(s, x);
  test::check_loop_laws_along(s, x, 3.0, e);
  CHECK(e.checked == 40);
  CHECK(e.algorithms < 1e-10);
  CHECK(e.accelerations < 1e-10);
  CHECK(e.power < 1e-10);
  CHECK(e.residual < 1e-12);
}

TEST_CASE("an assembly with the cut joint turned over is refused, naming the joint") {
  // The cut revolute's rows keep j6's axis normal to two axes of its
  // frame_a, which the axis reversed meets too: from some guesses Newton's
  // method closes Bricard's linkage that way, which is not the mechanism.
  const auto s = bricard<false>();
  std::mt19937 rng(52);
  int turned = 0, closed = 0;
  for (int k = 0; k < 100; ++k) {
    auto x = test::random_state(s, rng);
    try {
      close_loops<>(s, x);
      ++closed;
      CHECK_NOTHROW(check_loops(s, x));
    } catch (const parameter_error& e) {
      const std::string what = e.what();
      if (what.find("turned over") == std::string::npos) continue;  // did not close at all
      ++turned;
      CHECK(what.find("\"j6\"") != std::string::npos);
      // x is the assembly Newton found: closed, and refused as a state too.
      CHECK(loop_residual(s, x).max_phi() < 1e-9);
      CHECK_THROWS_WITH(check_loops(s, x), Catch::Contains("turned over"));
    }
  }
  CHECK(turned > 0);
  CHECK(closed > 0);
}
