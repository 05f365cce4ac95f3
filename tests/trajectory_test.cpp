// simulate() with output times: the states at those times through the dense
// output, projected where the scene needs it, with the run's cost; against a
// closed form, the run to one end time, the four-bar's loop, and bad input.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

using namespace flange;
using Catch::Matchers::Contains;

namespace {
/// A mass on a spring along x (gravity along −y does no work on it):
/// s(t) = s0·cos(ω·t), ω = √(c/m) = 2.
auto oscillator() {
  return scene(World<"world">{}, Prismatic<"slide", axis::x, double, axis_law::spring_damper>({.c = 4.0}),
               Body<"mass">({.m = 1.0}), connect<"world.frame_b", "slide.frame_a">,
               connect<"slide.frame_b", "mass.frame_a">);
}
}  // namespace

TEST_CASE("a trajectory is the closed form at every requested time, and ends where simulate() ends") {
  const auto s = oscillator();
  const auto x0 = initial_state<"slide">(s, {.q = 0.1});
  const auto times = output_times(0.0, 10.0, 0.01);
  REQUIRE(times.size() == 1001);
  CHECK(times.back() == 10.0);
  const simulate_options o{.tolerance = 1e-10};
  const auto tr = simulate(s, x0, times, o);
  REQUIRE(tr.size() == times.size());
  double worst = 0;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    CHECK(tr.t[k] == times[k]);
    worst = std::max(worst, std::abs(tr.x[k][0] - 0.1 * std::cos(2 * tr.t[k])));
    worst = std::max(worst, std::abs(tr.x[k][1] + 0.2 * std::sin(2 * tr.t[k])));
  }
  // dopri5 at 1e-10: each step's error within 1e-10·(1 + |x|), summed over
  // the steps (a neutral oscillator does not amplify them), which the
  // 4th-order dense output between steps does not exceed (linear
  // interpolation between steps of ~0.03 s would be ~5e-5 off). Measured: 6e-10.
  const double bound = static_cast<double>(tr.steps) * 1.1e-10;
  CHECK(worst < bound);
  CHECK(worst > 0);  // a sample that only copied x0 would not get here
  // The samples do not change the steps: the last state is simulate()'s, bit for bit.
  long observed = -1;
  const auto x1 = simulate(s, x0, 0.0, 10.0, o, [&](const auto&, double) { ++observed; });
  CHECK(std::memcmp(&tr.x.back(), &x1, sizeof x1) == 0);
  CHECK(tr.steps == observed);
  CHECK(tr.rhs_evals > 6 * tr.steps);  // dopri5: six evaluations a step, first-same-as-last
  CHECK(tr.rhs_evals < 7 * tr.steps + 10);
  // Backward in time from there: back to x0 to the same error.
  const auto back = simulate(s, x1, output_times(10.0, 0.0, 0.5), o);
  CHECK(back.t.back() == 0.0);
  CHECK(std::abs(back.x.back()[0] - 0.1) < 2 * bound);
}

TEST_CASE("every requested time is in the trajectory, the last one too, whatever t1 the run ends on") {
  // The last step ends on t1 to round-off (t + (t1 − t) need not be t1):
  // over many end times, none is left out.
  const auto s = oscillator();
  const auto x0 = initial_state<"slide">(s, {.q = 0.1});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.1, 10.0);
  for (int k = 0; k < 200; ++k) {
    const double t1 = u(rng);
    const auto times = output_times(0.0, t1, t1 / 3);
    const auto tr = simulate(s, x0, times, {.tolerance = 1e-6});
    REQUIRE(tr.size() == times.size());
    CHECK(tr.t.back() == t1);
    const auto x1 = simulate(s, x0, 0.0, t1, {.tolerance = 1e-6});
    CHECK(std::memcmp(&tr.x.back(), &x1, sizeof x1) == 0);
  }
}

TEST_CASE("a trajectory of a loop scene is on its loop at every sample, not only at the steps' ends") {
  const auto fb = models::fourbar({});
  decltype(fb)::state_type x0{0.3, 1.3, 2.4, 5.0, 0, 0};
  close_loops<"crank_pivot">(fb, x0);
  const auto tr = simulate(fb, x0, output_times(0.0, 20.0, 0.0137), {.tolerance = 1e-6});
  double phi = 0, phid = 0;
  for (const auto& x : tr.x) {
    const auto r = loop_residual(fb, x);
    phi = std::max(phi, r.max_phi());
    phid = std::max(phid, r.max_phid());
  }
  CHECK(phi <= 1e-10);
  CHECK(phid <= 1e-10);
}

TEST_CASE("bad output times are refused, naming the time") {
  const auto s = oscillator();
  const auto x0 = initial_state<"slide">(s, {.q = 0.1});
  CHECK_THROWS_WITH(simulate(s, x0, std::vector<double>{0.0}), Contains("1 output time(s)"));
  CHECK_THROWS_WITH(simulate(s, x0, {0.0, 1.0, 0.5}), Contains("strictly increasing") && Contains("time 2 = 0.5"));
  CHECK_THROWS_WITH(simulate(s, x0, {0.0, NAN, 1.0}), Contains("output time 1 is nan"));
  CHECK_THROWS_WITH(output_times(0.0, 1.0, -0.1), Contains("dt = -0.1"));
  CHECK_THROWS_WITH(output_times(1.0, 1.0, 0.1), Contains("t0 != t1"));
  // A last interval shorter than dt ends on t1 exactly; one within round-off of dt is not split.
  CHECK(output_times(0.0, 1.0, 0.3) == std::vector<double>{0.0, 0.3, 0.6, 0.8999999999999999, 1.0});
  CHECK(output_times(0.0, 1.0, 0.1).size() == 11);
}
