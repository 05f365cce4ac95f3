// Where flange cuts a loop, and that the motion does not depend on it: the
// writing order's cut (the last joint of a loop) is kept where it is good,
// and moved where it would leave a joint moving no mass or where the joint
// cannot be cut. Checked against the same mechanism cut elsewhere by hand
// (a second formulation: another tree, other coordinates, other
// constraints), through the bodies' world positions, and by energy.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>
#include <string_view>
#include <tuple>

#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>

#include "loop_laws.hpp"
#include "scene_orders.hpp"

using namespace flange;

namespace {

/// Modelica's MultiBody.Examples.Loops.Fourbar1: six revolutes and a
/// prismatic joint in one spatial loop. Its parts in the order of its
/// source: the World, the components (j5 written last: cutting it would
/// leave j3 and j4 moving nothing with mass), then the connections.
auto fourbar1_parts() {
  return std::make_tuple(
      World<"world">{}, Revolute<"j1", axis::x>{}, Prismatic<"j2", axis::x>({}),
      BodyCylinder<"b1">({.r = Vec3d(0, 0.5, 0.1), .diameter = 0.05}),
      BodyCylinder<"b2">({.r = Vec3d(0, 0.2, 0), .diameter = 0.05}),
      BodyCylinder<"b3">({.r = Vec3d(-1, 0.3, 0.1), .diameter = 0.05}), Revolute<"rev", axis::y>{},
      Revolute<"rev1", axis::z>{}, Revolute<"j3", axis::x>{}, Revolute<"j4", axis::y>{}, Revolute<"j5", axis::z>{},
      FixedTranslation<"b0">({.d = Vec3d(1.2, 0, 0)}),  //
      connect<"j2.frame_b", "b2.frame_a">, connect<"j1.frame_b", "b1.frame_a">, connect<"rev.frame_a", "b2.frame_b">,
      connect<"rev.frame_b", "rev1.frame_a">, connect<"rev1.frame_b", "b3.frame_a">,
      connect<"world.frame_b", "j1.frame_a">, connect<"b1.frame_b", "j3.frame_a">, connect<"j3.frame_b", "j4.frame_a">,
      connect<"j4.frame_b", "j5.frame_a">, connect<"j5.frame_b", "b3.frame_b">, connect<"b0.frame_a", "world.frame_b">,
      connect<"b0.frame_b", "j2.frame_a">);
}

/// Fourbar1 in its source's order (Order 0), with j1 moved after the last
/// component (Order 1: cut there by writing order), or with j2 moved there
/// (Order 2: a Prismatic has a force input, which a cut joint cannot have).
template <int Order>
auto fourbar1() {
  constexpr std::size_t n = std::tuple_size_v<decltype(fourbar1_parts())>, last_component = 11;
  if constexpr (Order == 0) return test::scene_of(fourbar1_parts());
  else return test::scene_in_order<test::moved_after<n>(Order, last_component)>(fourbar1_parts());
}

template <class S>
constexpr std::string_view cut_name() {
  return cut_joints<S>()[0];
}

/// The largest distance between the named frames of two runs, over their samples.
template <class SA, class SB, class TA, class TB, std::size_t N>
double largest_gap(const SA& a, const TA& ta, const SB& b, const TB& tb, const std::array<std::string_view, N>& frames) {
  double gap = 0;
  for (std::size_t k = 0; k < ta.size(); ++k) {
    const auto ra = recover(a, ta.t[k], ta.x[k]);
    const auto rb = recover(b, tb.t[k], tb.x[k]);
    for (const auto f : frames) gap = std::max(gap, (ra.frame(f).r - rb.frame(f).r).norm());
  }
  return gap;
}

}  // namespace

TEST_CASE("Modelica's Fourbar1 written in its source's order is cut where every joint moves mass") {
  using S0 = decltype(fourbar1<0>());
  using S1 = decltype(fourbar1<1>());
  using S2 = decltype(fourbar1<2>());
  // The writing order would cut j5; j3 and j4 would then carry only each
  // other. Of the loop's joints only j1 and j2 leave mass beyond every
  // joint, and j2 cannot be cut.
  STATIC_REQUIRE(S0::tree.n_cuts == 1);
  STATIC_REQUIRE(cut_name<S0>() == "j1");
  STATIC_REQUIRE(cut_name<S1>() == "j1");  // written last, and good: kept
  STATIC_REQUIRE(cut_name<S2>() == "j1");
  STATIC_REQUIRE(S0::n_v == 6);
  STATIC_REQUIRE(constraint_count<S0> == 5);  // a spatial revolute's cut
}

TEST_CASE("Fourbar1 moves the same whatever the writing order") {
  const auto s0 = fourbar1<0>();
  const auto s1 = fourbar1<1>();
  const auto s2 = fourbar1<2>();
  // All joints at 0 and j2 at −0.2 m close the loop (b3's two ends meet at
  // (0, 0.5, 0.1)); j2 slides at 0.5 m/s, and gravity does the rest.
  auto x0 = initial_state<"j2">(s0, {.q = -0.2, .v = 0.5});
  close_loops<"j2">(s0, x0);
  auto x1 = initial_state<"j2">(s1, {.q = -0.2, .v = 0.5});
  close_loops<"j2">(s1, x1);
  auto x2 = initial_state<"j2">(s2, {.q = -0.2, .v = 0.5});
  close_loops<"j2">(s2, x2);

  const auto times = output_times(0.0, 2.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  const auto t0 = simulate(s0, x0, times, o);
  const auto t1 = simulate(s1, x1, times, o);
  const auto t2 = simulate(s2, x2, times, o);
  const std::array<std::string_view, 3> frames{"b1.frame_b", "b2.frame_b", "b3.frame_a"};
  // Other writing orders: other numberings of one tree.
  CHECK(largest_gap(s0, t0, s1, t1, frames) < 1e-9);
  CHECK(largest_gap(s0, t0, s2, t2, frames) < 1e-9);
  // It moves (the comparison is not between resting mechanisms), and it
  // keeps its energy.
  const auto r_start = recover(s0, 0.0, t0.x.front());
  const auto r_end = recover(s0, 2.0, t0.x.back());
  CHECK((r_start.frame("b3.frame_a").r - r_end.frame("b3.frame_a").r).norm() > 0.02);
  CHECK(std::abs(r_end.energy() - r_start.energy()) < 1e-9 * std::max(1.0, std::abs(r_start.energy())));
}

namespace {
/// Where Fourbar1's joints sit in scene S's state: the tree's numbering.
template <class S>
std::array<int, 6> fourbar1_numbering() {
  return {S::template q_offset<"j2">(), S::template q_offset<"rev">(), S::template q_offset<"rev1">(),
          S::template q_offset<"j3">(),  S::template q_offset<"j4">(),  S::template q_offset<"j5">()};
}

/// Fourbar1 written in the order Seed shuffles its parts into (components
/// and connections mixed), started as the test above starts it: the largest
/// gap of its frames from the run `ref`, and its tree's numbering.
template <unsigned Seed, class Ref, class Tr>
std::pair<double, std::array<int, 6>> fourbar1_shuffled(const Ref& ref, const Tr& tr) {
  const auto s = test::shuffled_scene<Seed>(fourbar1_parts());
  using S = decltype(s);
  // j1 is its only good cut: any other leaves a joint moving no mass.
  STATIC_REQUIRE(cut_name<S>() == "j1");
  auto x = initial_state<"j2">(s, {.q = -0.2, .v = 0.5});
  close_loops<"j2">(s, x);
  const auto ts = simulate(s, x, tr.t, {.tolerance = 1e-12});
  const std::array<std::string_view, 3> frames{"b1.frame_b", "b2.frame_b", "b3.frame_a"};
  return {largest_gap(ref, tr, s, ts, frames), fourbar1_numbering<S>()};
}
}  // namespace

TEST_CASE("Fourbar1 written in shuffled orders of its components and connections moves the same") {
  const auto s0 = fourbar1<0>();
  auto x0 = initial_state<"j2">(s0, {.q = -0.2, .v = 0.5});
  close_loops<"j2">(s0, x0);
  const auto t0 = simulate(s0, x0, output_times(0.0, 2.0, 0.05), {.tolerance = 1e-12});
  double worst = 0;
  std::set<std::array<int, 6>> numberings{fourbar1_numbering<decltype(s0)>()};
  auto add = [&](std::pair<double, std::array<int, 6>> r) {
    worst = std::max(worst, r.first);
    numberings.insert(r.second);
  };
  add(fourbar1_shuffled<1>(s0, t0));
  add(fourbar1_shuffled<2>(s0, t0));
  add(fourbar1_shuffled<3>(s0, t0));
  CHECK(numberings.size() == 4);  // four numberings of the tree
  CHECK(worst < 1e-9);
}

namespace {
/// A scene of the given components (any order, the World among them) joined
/// as models::fourbar joins its own.
template <class... C>
auto fourbar_of(const C&... components) {
  return scene(components..., connect<"world.frame_b", "crank_pivot.frame_a">,
               connect<"crank_pivot.frame_b", "crank.frame_a">, connect<"crank.frame_b", "crank_pin.frame_a">,
               connect<"crank_pin.frame_b", "coupler.frame_a">, connect<"coupler.frame_b", "rocker_pin.frame_a">,
               connect<"rocker_pin.frame_b", "rocker.frame_a">, connect<"world.frame_b", "ground.frame_a">,
               connect<"ground.frame_b", "rocker_pivot.frame_a">, connect<"rocker.frame_b", "rocker_pivot.frame_b">);
}

/// models::fourbar with joint Last (0 crank_pivot, 1 crank_pin, 2
/// rocker_pin) written last, which cuts it there.
template <int Last>
auto fourbar_cut_at(const models::fourbar_params& p) {
  using models::bar;
  const auto j0 = Revolute<"crank_pivot", axis::z>{};
  const auto j1 = Revolute<"crank_pin", axis::z>{};
  const auto j2 = Revolute<"rocker_pin", axis::z>{};
  const auto j3 = Revolute<"rocker_pivot", axis::z>{};
  const auto with = [&](auto a, auto b, auto c, auto d) {
    return fourbar_of(World<"world">({.g = p.g}), a, b, c, bar<"crank">(p.crank, p.m_crank),
                      bar<"coupler">(p.coupler, p.m_coupler), bar<"rocker">(p.rocker, p.m_rocker),
                      FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}), d);
  };
  if constexpr (Last == 0) return with(j1, j2, j3, j0);
  else if constexpr (Last == 1) return with(j0, j2, j3, j1);
  else return with(j0, j1, j3, j2);
}

/// models::fourbar at crank angle θ2 = 1 rad with the crank turning at
/// `rate`, closed holding the crank: its state, and its four joint angles
/// (crank pivot, crank pin, rocker pin, rocker pivot) for the scenes cut elsewhere.
std::pair<std::array<double, 6>, std::array<double, 4>> fourbar_start(const models::fourbar_params& p, double rate) {
  const auto ref = models::fourbar(p);
  const double th2 = 1.0;
  const auto q = models::fourbar_coordinates(p, th2, models::freudenstein_rocker(p, th2));
  std::array<double, 6> xr{q[0], q[1], q[2], rate, 0, 0};
  close_loops<"crank_pivot">(ref, xr);
  return {xr, {xr[0], xr[1], xr[2], recover(ref, 0.0, xr).internal<"rocker_pivot", "phi">()}};
}

/// x for scene S from the four-bar's joint angles (all four) and the crank
/// pin's rate, closed holding the crank pin.
template <class S>
auto state_from_angles(const S& s, const std::array<double, 4>& phi, double crank_pin_rate) {
  typename S::state_type x{};
  constexpr std::array<std::string_view, 4> names{"crank_pivot", "crank_pin", "rocker_pin", "rocker_pivot"};
  for (int k = 0; k < 4; ++k) {
    const int c = S::index_of(names[k]);
    if (S::tree.cut_of[c] < 0) x[S::tree.q_offset[c]] = phi[k];
  }
  x[S::n_q + S::tree.v_offset[S::index_of("crank_pin")]] = crank_pin_rate;
  close_loops<"crank_pin">(s, x);
  return x;
}

/// The planar four-bar with a massless coupler (a FixedTranslation, no
/// body), and the rocker pin written last: the writing order would cut it
/// and leave the crank pin carrying the coupler alone. The rocker pivot,
/// written before it, is a good cut.
auto fourbar_massless_coupler(const models::fourbar_params& p) {
  using models::bar;
  return fourbar_of(World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
                    Revolute<"crank_pin", axis::z>{}, FixedTranslation<"coupler">({.d = Vec3d(p.coupler, 0, 0)}),
                    bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
                    Revolute<"rocker_pivot", axis::z>{}, Revolute<"rocker_pin", axis::z>{});
}
}  // namespace

TEST_CASE("a four-bar whose coupler has no mass runs and moves as the four-bar with a zero-mass coupler body") {
  models::fourbar_params p;
  p.m_coupler = 0;
  const auto ref = models::fourbar(p);  // cut at rocker_pivot: the coupler body has m = 0, the rocker beyond it
  const auto fb = fourbar_massless_coupler(p);
  using S = decltype(fb);
  STATIC_REQUIRE(cut_name<S>() == "rocker_pivot");  // of the good cuts, the joint written last

  const auto xr = fourbar_start(p, 2.0).first;
  auto x = initial_state<"crank_pivot", "crank_pin", "rocker_pin">(fb, {.q = xr[0]}, {.q = xr[1], .v = xr[4]},
                                                                   {.q = xr[2]});
  close_loops<"crank_pin">(fb, x);

  const auto times = output_times(0.0, 2.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  const auto tr = simulate(ref, xr, times, o);
  const auto tf = simulate(fb, x, times, o);
  const std::array<std::string_view, 2> frames{"crank.frame_b", "rocker.frame_a"};
  CHECK(largest_gap(ref, tr, fb, tf, frames) < 1e-9);
  CHECK(std::abs(recover(fb, 2.0, tf.x.back()).energy() - recover(fb, 0.0, tf.x.front()).energy()) < 1e-9);
}

namespace {
/// models::fourbar's bars, its rocker pivot (written last) driven by a
/// motor of constant torque 1 N m.
auto driven_fourbar(const models::fourbar_params& p) {
  using models::bar;
  return fourbar_of(World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
                    Revolute<"crank_pin", axis::z>{}, bar<"coupler">(p.coupler, p.m_coupler),
                    Revolute<"rocker_pin", axis::z>{}, bar<"rocker">(p.rocker, p.m_rocker),
                    FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
                    revolute<"rocker_pivot", axis::z>([](auto t) { return 0.0 * t + 1.0; }));
}
}  // namespace

TEST_CASE("a loop whose last-written joint is driven is cut at another joint") {
  const models::fourbar_params p;
  auto fb = driven_fourbar(p);
  using S = decltype(fb);
  STATIC_REQUIRE(cut_name<S>() == "rocker_pin");  // of the joints that can be cut, the one written last
  STATIC_REQUIRE(S::tree.cut_of[S::index_of("rocker_pivot")] < 0);
  // The motor's constant torque τ = 1 N m does the work τ·(φ(t) − φ(0)):
  // the energy (kinetic and gravity's) grows by that much.
  const auto ref = models::fourbar(p);
  const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  std::array<double, 6> xr{q[0], q[1], q[2], 0, 0, 0};
  close_loops<"crank_pivot">(ref, xr);
  auto x = initial_state<"crank_pivot", "crank_pin", "rocker_pivot">(
      fb, {.q = xr[0]}, {.q = xr[1]}, {.q = recover(ref, 0.0, xr).internal<"rocker_pivot", "phi">()});
  close_loops<"rocker_pivot">(fb, x);
  const auto r0 = recover(fb, 0.0, x);
  const auto x1 = simulate(fb, x, 0.0, 1.0, {.tolerance = 1e-11});
  const auto r1 = recover(fb, 1.0, x1);
  const double work = 1.0 * (r1.internal<"rocker_pivot", "phi">() - r0.internal<"rocker_pivot", "phi">());
  CHECK(std::abs(r1.energy() - r0.energy() - work) < 1e-8);
}

TEST_CASE("the planar four-bar cut at each of its joints moves as the one cut at the rocker pivot") {
  const models::fourbar_params p;
  const auto ref = models::fourbar(p);
  const auto f0 = fourbar_cut_at<0>(p);
  const auto f1 = fourbar_cut_at<1>(p);
  const auto f2 = fourbar_cut_at<2>(p);
  STATIC_REQUIRE(cut_name<decltype(f0)>() == "crank_pivot");
  STATIC_REQUIRE(cut_name<decltype(f1)>() == "crank_pin");
  STATIC_REQUIRE(cut_name<decltype(f2)>() == "rocker_pin");
  const auto start_state = fourbar_start(p, 2.0);
  const auto& xr = start_state.first;
  const auto& phi = start_state.second;
  const auto times = output_times(0.0, 2.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  const auto tr = simulate(ref, xr, times, o);
  const std::array<std::string_view, 2> frames{"crank.frame_b", "rocker.frame_a"};
  const auto x0 = state_from_angles(f0, phi, xr[4]);
  CHECK(largest_gap(ref, tr, f0, simulate(f0, x0, times, o), frames) < 1e-9);
  const auto x2 = state_from_angles(f2, phi, xr[4]);
  CHECK(largest_gap(ref, tr, f2, simulate(f2, x2, times, o), frames) < 1e-9);
  // The crank pin cut: hold the crank pivot at the reference's rate.
  auto x1 = initial_state<"crank_pivot", "rocker_pin", "rocker_pivot">(f1, {.q = phi[0], .v = xr[3]}, {.q = phi[2]},
                                                                       {.q = phi[3]});
  close_loops<"crank_pivot">(f1, x1);
  CHECK(largest_gap(ref, tr, f1, simulate(f1, x1, times, o), frames) < 1e-9);
}

TEST_CASE("the loop laws hold on Fourbar1 in three writing orders, the massless coupler and the driven four-bar") {
  // The driven four-bar's motor is in the power balance as a joint force.
  std::mt19937 rng(52);
  test::loop_law_errors e;
  const models::fourbar_params p;
  test::check_loop_laws(fourbar1<0>(), rng, e);
  test::check_loop_laws(fourbar1<1>(), rng, e);
  test::check_loop_laws(fourbar1<2>(), rng, e);
  test::check_loop_laws(fourbar_massless_coupler(p), rng, e);
  test::check_loop_laws(driven_fourbar(p), rng, e);
  CHECK(e.checked == 50);
  CHECK(e.algorithms < 1e-10);
  CHECK(e.accelerations < 1e-10);
  CHECK(e.power < 1e-10);
  CHECK(e.residual < 1e-12);
}

namespace {
/// models::fourbar's components and connections as one tuple, for shuffling.
auto fourbar_parts(const models::fourbar_params& p) {
  using models::bar;
  return std::make_tuple(
      World<"world">({.g = p.g}), Revolute<"crank_pivot", axis::z>{}, bar<"crank">(p.crank, p.m_crank),
      Revolute<"crank_pin", axis::z>{}, bar<"coupler">(p.coupler, p.m_coupler), Revolute<"rocker_pin", axis::z>{},
      bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
      Revolute<"rocker_pivot", axis::z>{}, connect<"world.frame_b", "crank_pivot.frame_a">,
      connect<"crank_pivot.frame_b", "crank.frame_a">, connect<"crank.frame_b", "crank_pin.frame_a">,
      connect<"crank_pin.frame_b", "coupler.frame_a">, connect<"coupler.frame_b", "rocker_pin.frame_a">,
      connect<"rocker_pin.frame_b", "rocker.frame_a">, connect<"world.frame_b", "ground.frame_a">,
      connect<"ground.frame_b", "rocker_pivot.frame_a">, connect<"rocker.frame_b", "rocker_pivot.frame_b">);
}

constexpr std::array<std::string_view, 4> fourbar_joints{"crank_pivot", "crank_pin", "rocker_pin", "rocker_pivot"};

/// The four joints' angles and rates, read by name (a cut joint's from its frames).
template <class S>
std::array<std::pair<double, double>, 4> fourbar_angles(const S& s, const typename S::state_type& x) {
  auto read = [](const auto& j) { return std::pair{j.q, j.v}; };
  return {read(get_joint<"crank_pivot">(s, x)), read(get_joint<"crank_pin">(s, x)),
          read(get_joint<"rocker_pin">(s, x)), read(get_joint<"rocker_pivot">(s, x))};
}

/// The largest difference of two runs' joint angles (the short way round)
/// and rates over their samples.
template <class SA, class SB, class TA, class TB>
double largest_joint_gap(const SA& a, const TA& ta, const SB& b, const TB& tb) {
  double gap = 0;
  for (std::size_t k = 0; k < ta.size(); ++k) {
    const auto ja = fourbar_angles(a, ta.x[k]), jb = fourbar_angles(b, tb.x[k]);
    for (int i = 0; i < 4; ++i)
      gap = std::max({gap, std::abs(std::remainder(ja[i].first - jb[i].first, 2 * std::numbers::pi)),
                      std::abs(ja[i].second - jb[i].second)});
  }
  return gap;
}

/// Runs the four-bar written in the order Seed gives from the angles and
/// rates `joints` (every joint's), against the reference run.
template <unsigned Seed, class Ref, class Tr>
std::pair<double, std::string_view> run_shuffled(const models::fourbar_params& p, const Ref& ref, const Tr& tr,
                                                 const std::array<std::pair<double, double>, 4>& joints) {
  const auto s = test::shuffled_scene<Seed>(fourbar_parts(p));
  using S = decltype(s);
  typename S::state_type x{};
  for (int k = 0; k < 4; ++k) {
    const int c = S::index_of(fourbar_joints[k]);
    if (S::tree.cut_of[c] >= 0) continue;
    x[S::tree.q_offset[c]] = joints[k].first;
    x[S::n_q + S::tree.v_offset[c]] = joints[k].second;
  }
  close_loops<>(s, x);  // closed already, to round-off
  const auto ts = simulate(s, x, tr.t, {.tolerance = 1e-12});
  return {largest_joint_gap(ref, tr, s, ts), cut_joints<S>()[0]};
}
}  // namespace

TEST_CASE("the planar four-bar written in shuffled orders of its components and connections moves the same") {
  // Each order is cut at the last-written of its joints and builds its tree
  // from there; the runs are compared joint by joint, by name.
  const models::fourbar_params p;
  const auto ref = models::fourbar(p);
  const auto xr = fourbar_start(p, 2.0).first;
  const auto tr = simulate(ref, xr, output_times(0.0, 2.0, 0.05), {.tolerance = 1e-12});
  const auto joints = fourbar_angles(ref, xr);
  double worst = 0;
  std::set<std::string_view> cuts;
  auto add = [&](std::pair<double, std::string_view> r) {
    worst = std::max(worst, r.first);
    cuts.insert(r.second);
  };
  add(run_shuffled<1>(p, ref, tr, joints));  // cut at the crank pin
  add(run_shuffled<2>(p, ref, tr, joints));  // at the crank pivot
  add(run_shuffled<4>(p, ref, tr, joints));  // at the rocker pin
  add(run_shuffled<5>(p, ref, tr, joints));  // at the rocker pivot
  CHECK(cuts.size() == 4);
  CHECK(worst < 1e-9);
}

TEST_CASE("a cut joint's angle reads continuous along a run: the four-bar cut at its spinning crank's pivot") {
  // Which coordinates are angles, unwrapped when a cut joint is read.
  STATIC_REQUIRE(periodic_coordinates<Revolute<"r">>() == std::array{true});
  STATIC_REQUIRE(periodic_coordinates<Prismatic<"p">>() == std::array{false});
  STATIC_REQUIRE(periodic_coordinates<Universal<"u">>() == std::array{true, true});
  STATIC_REQUIRE(periodic_coordinates<Cylindrical<"c">>() == std::array{false, true});
  STATIC_REQUIRE(periodic_coordinates<Planar<"p">>() == std::array{false, false, true});
  STATIC_REQUIRE(periodic_coordinates<Spherical<"s">>() == std::array{false, false, false, false});
  // No gravity, the crank spun at 12 rad/s: it makes turns.
  // The reference holds the crank pivot in its tree (its angle is a state
  // coordinate); the other scene cuts it there (its angle is read from its
  // frames).
  const models::fourbar_params p{.g = Vec3d::Zero()};
  const auto ref = models::fourbar(p);
  const auto f0 = fourbar_cut_at<0>(p);
  STATIC_REQUIRE(cut_name<decltype(f0)>() == "crank_pivot");
  const auto start_state = fourbar_start(p, 12.0);
  const auto& xr = start_state.first;
  const auto& phi = start_state.second;
  const auto times = output_times(0.0, 3.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  const auto tr = simulate(ref, xr, times, o);
  const auto tc = simulate(f0, state_from_angles(f0, phi, xr[4]), times, o);
  const auto read = get_joint<"crank_pivot">(f0, tc);
  const auto ref_read = get_joint<"crank_pivot">(ref, tr);
  REQUIRE(read.size() == times.size());
  constexpr int qc = decltype(ref)::q_offset<"crank_pivot">();
  double gap = 0, wrapped_gap = 0, near_gap = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double q_ref = tr.x[k][qc];
    CHECK(ref_read[k].q == q_ref);  // a tree joint reads its state coordinate
    gap = std::max({gap, std::abs(read[k].q - q_ref), std::abs(read[k].v - tr.x[k][decltype(ref)::n_q + qc])});
    wrapped_gap = std::max(wrapped_gap, std::abs(get_joint<"crank_pivot">(f0, tc.x[k]).q - q_ref));
    // One reading unwrapped toward the one before: the same as along the run.
    if (k > 0) near_gap = std::max(near_gap, std::abs(get_joint<"crank_pivot">(f0, tc.x[k], read[k - 1]).q - read[k].q));
  }
  CHECK(tr.x.back()[qc] - tr.x.front()[qc] > 6 * std::numbers::pi);  // three turns and more
  // The two runs agree in the frames' positions to 1e-9 (the test above);
  // the angle's error is that over the crank's 0.3 m.
  CHECK(gap < 1e-9);  // measured 1e-10
  CHECK(near_gap == 0);
  CHECK(wrapped_gap > 4 * std::numbers::pi);  // read one at a time, it jumps back by whole turns
}

namespace {
/// The planar four-bar with a motor at the crank pivot whose torque reads
/// the rocker pivot by name (a PD law on the rocker's angle), written with
/// the rocker pivot last (cut there: the input reads it from its frames) or
/// with the crank pin last (cut there: the rocker pivot is in the tree).
template <bool RockerPivotCut>
auto fourbar_rocker_servo(const models::fourbar_params& p) {
  using models::bar;
  auto torque = [](auto, const auto& x) { return 4.0 * (1.2 - q<"rocker_pivot">(x)) - 0.5 * v<"rocker_pivot">(x); };
  const auto pivot = Revolute<"rocker_pivot", axis::z>{};
  const auto pin = Revolute<"crank_pin", axis::z>{};
  const auto with = [&](auto a, auto b) {
    return fourbar_of(World<"world">({.g = p.g}), revolute<"crank_pivot", axis::z>(torque),
                      bar<"crank">(p.crank, p.m_crank), bar<"coupler">(p.coupler, p.m_coupler),
                      Revolute<"rocker_pin", axis::z>{}, bar<"rocker">(p.rocker, p.m_rocker),
                      FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}), a, b);
  };
  if constexpr (RockerPivotCut) return with(pin, pivot);
  else return with(pivot, pin);
}
}  // namespace

TEST_CASE("an input reads a cut joint by name as it reads a tree joint") {
  const models::fourbar_params p;
  const auto cut = fourbar_rocker_servo<true>(p);
  const auto tree = fourbar_rocker_servo<false>(p);
  STATIC_REQUIRE(cut_name<decltype(cut)>() == "rocker_pivot");
  STATIC_REQUIRE(cut_name<decltype(tree)>() == "crank_pin");
  const auto ref = models::fourbar(p);  // the same four-bar unpowered, cut at the rocker pivot
  const auto start_state = fourbar_start(p, 0.5);
  const auto& xr = start_state.first;
  const auto& phi = start_state.second;
  const auto times = output_times(0.0, 2.0, 0.05);
  const simulate_options o{.tolerance = 1e-12};
  // Both from the reference's angles, closed holding the crank pivot at its rate.
  const auto start_at = [&](const auto& s) {
    using S = std::remove_cvref_t<decltype(s)>;
    typename S::state_type x{};
    constexpr std::array<std::string_view, 4> names{"crank_pivot", "crank_pin", "rocker_pin", "rocker_pivot"};
    for (int k = 0; k < 4; ++k)
      if (const int c = S::index_of(names[k]); S::tree.cut_of[c] < 0) x[S::tree.q_offset[c]] = phi[k];
    x[S::n_q + S::template v_offset<"crank_pivot">()] = xr[3];
    close_loops<"crank_pivot">(s, x);
    return x;
  };
  const auto tc = simulate(cut, start_at(cut), times, o);
  const auto tt = simulate(tree, start_at(tree), times, o);
  const auto tu = simulate(ref, xr, times, o);
  const std::array<std::string_view, 2> frames{"crank.frame_b", "rocker.frame_a"};
  // The motor spins the crank up to 17 turns in 2 s; the two runs' frames
  // agree to 1e-10 and better (the crank's angle to 3e-11 of its 106 rad).
  CHECK(largest_gap(cut, tc, tree, tt, frames) < 1e-9);
  CHECK(largest_gap(cut, tc, ref, tu, frames) > 1e-2);  // the motor moves it
  // Read in dual numbers too: the exact Jacobian equals central differences.
  const auto x = tc.x[20];
  const auto J = jacobian(cut, 1.0, x);
  const auto Jfd = jacobian_finite_difference(cut, 1.0, x);
  CHECK((J - Jfd).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, J.cwiseAbs().maxCoeff()));
  // A view made without the scene cannot place the cut joint.
  const auto view = state_view<decltype(cut)>(x.data(), x.data() + 3);
  CHECK_THROWS_WITH(q<"rocker_pivot">(view), Catch::Contains("joint \"rocker_pivot\" closes a loop"));
  CHECK(q<"crank_pivot">(view) == x[0]);
}
