// Ensembles (flange/ensemble/): the exact pendulum period over a sweep of
// amplitudes, rows equal to simulate() bit for bit, serial = TBB on 2 and all
// threads bit for bit, failing cases recorded while the others go on, the
// CSV, and seeded sampling.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>

#include <flange/ensemble/ensemble.hpp>
#include <flange/ensemble/tbb.hpp>
#include <flange/flange.hpp>
#include <flange/models/controlled_crane.hpp>
#include <flange/simulate/bulirsch_stoer.hpp>

using namespace flange;
namespace en = flange::ensemble;

namespace {

/// A simple pendulum: a point mass m on a massless rod of length L.
auto pendulum(double L, double m) {
  return scene(World<"world">({.g = {0, -9.81, 0}}), Revolute<"pivot", axis::z>{},
               FixedTranslation<"rod">({.d = {L, 0, 0}}), PointMass<"bob">({.m = m}),
               connect<"world.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "bob.frame_a">);
}
using Pendulum = decltype(pendulum(1.0, 1.0));

/// The crane sweep of examples/crane_sweep.cpp: gains and load masses.
auto crane_setup = [](const std::array<double, 2>& c) {
  models::controlled_crane_params p;
  p.m_load = c[1];
  p.controller = {.kp = c[0], .kd = 2 * 0.7 * std::sqrt(c[0] * (p.m_cart + c[1])), .target = 1.0};
  return std::pair{models::controlled_crane(p), models::controlled_crane_rest()};
};
double swing(const auto&, double, const auto& x) { return std::abs(x[1] + std::numbers::pi / 2); }

template <class R>
void require_identical(const R& a, const R& b) {
  REQUIRE(a.rows.size() == b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const auto &x = a.rows[i], &y = b.rows[i];
    REQUIRE(x.index == i);
    REQUIRE(y.index == i);
    REQUIRE(x.ok == y.ok);
    REQUIRE(x.rhs_evals == y.rhs_evals);
    REQUIRE(x.steps == y.steps);
    REQUIRE(x.reason == y.reason);
    for (std::size_t k = 0; k < x.values.size(); ++k)
      REQUIRE(std::memcmp(&x.values[k], &y.values[k], sizeof(double)) == 0);  // bit for bit, NaN included
  }
}

}  // namespace

TEST_CASE("a sweep over the pendulum's amplitude gives the exact period 4·sqrt(L/g)·K(sin(θ0/2)) at every case") {
  const double L = 0.8, g = 9.81;
  const auto cases = en::grid<1>({"theta0"}, {en::linspace(0.1, 3.0, 30)});
  // Released at rest at θ0 > 0, θ̇ first goes negative and comes back through
  // zero, upward, at the far turning point: half a period.
  auto study = en::make([&](const std::array<double, 1>& c) {
    return std::pair{pendulum(L, 0.3), Pendulum::state_type{c[0] - std::numbers::pi / 2, 0.0}};
  }, 0.0, 6.0, {.tolerance = 1e-12, .dt = 1e-3},
                         en::crossing("half_period", [](const auto&, double, const auto& x) { return x[1]; }, +1));
  const auto res = study.run(cases);
  REQUIRE(res.failed() == 0);
  double worst = 0;
  for (const auto& r : res.rows) {
    const double theta0 = cases[r.index][0];
    const double exact = 4 * std::sqrt(L / g) * std::comp_ellint_1(std::sin(theta0 / 2));
    REQUIRE(std::isfinite(r.values[0]));  // the crossing was found
    worst = std::max(worst, std::abs(2 * r.values[0] - exact) / exact);
  }
  INFO("largest relative error of the period over 30 amplitudes: " << worst);
  // The same with Bulirsch–Stoer's dense output in place of dopri5's.
  auto bs = en::make_with<en::method::bulirsch_stoer>(
      [&](const std::array<double, 1>& c) {
        return std::pair{pendulum(L, 0.3), Pendulum::state_type{c[0] - std::numbers::pi / 2, 0.0}};
      },
      0.0, 6.0, {.tolerance = 1e-12, .dt = 1e-3},
      en::crossing("half_period", [](const auto&, double, const auto& x) { return x[1]; }, +1));
  const auto res_bs = bs.run(cases);
  REQUIRE(res_bs.failed() == 0);
  double worst_bs = 0;
  for (const auto& r : res_bs.rows) {
    const double exact = 4 * std::sqrt(L / g) * std::comp_ellint_1(std::sin(cases[r.index][0] / 2));
    REQUIRE(std::isfinite(r.values[0]));
    worst_bs = std::max(worst_bs, std::abs(2 * r.values[0] - exact) / exact);
  }
  INFO("the same with Bulirsch–Stoer: " << worst_bs);
  CHECK(worst_bs < 1e-9);
  // dopri5 at 1e-12: its dense output is accurate to about the tolerance,
  // and near the turning point θ̇ changes at |θ̈| ≥ g/L·sin(0.1), so the
  // crossing time is good to ~1e-11; 1e-9 leaves a margin for θ0 = 3.0,
  // where the period is 3.2× the small-amplitude one.
  CHECK(worst < 1e-9);
}

TEST_CASE("a case's row equals simulate()'s bit for bit, evaluations included") {
  const auto cases = en::grid<2>({"kp", "m_load"}, {en::linspace(4, 40, 4), en::linspace(0.2, 2.0, 3)});
  const simulate_options in{.tolerance = 1e-9, .dt = 1e-3};
  const double t0 = 0, t1 = 5.0;
  auto study = en::make(crane_setup, t0, t1, in, en::final_state{});
  const auto res = study.run(cases);
  REQUIRE(res.failed() == 0);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    auto [crane, x0] = crane_setup(cases[i]);
    long steps = -1;  // the observer sees the start and every step
    const auto x = simulate(crane, x0, t0, t1, in, [&](const auto&, double) { ++steps; });
    for (int k = 0; k < 4; ++k) REQUIRE(std::memcmp(&res.rows[i].values[k], &x[k], sizeof(double)) == 0);
    REQUIRE(res.rows[i].steps == steps);
  }
}

TEST_CASE("states_at writes each case's states at the times as simulate returns them, on any thread count") {
  const auto cases = en::grid<2>({"kp", "m_load"}, {en::linspace(4, 40, 3), en::linspace(0.2, 2.0, 2)});
  const auto times = output_times(0.0, 3.0, 0.1);
  const std::size_t n = times.size(), w = models::controlled_crane_scene::n_state;
  for (int threads : {1, 2}) {
    std::vector<double> out(cases.size() * n * w, std::numeric_limits<double>::quiet_NaN());
    auto study = en::make(crane_setup, times.front(), times.back(), {.tolerance = 1e-9},
                          en::states_at(times.data(), n, out.data()));
    const auto res = threads == 1 ? study.run(cases) : study.run(cases, en::tbb_threads{threads});
    REQUIRE(res.failed() == 0);
    for (std::size_t i = 0; i < cases.size(); ++i) {
      auto [crane, x0] = crane_setup(cases[i]);
      const auto tr = simulate(crane, x0, times, {.tolerance = 1e-9});
      for (std::size_t k = 0; k < n; ++k)
        REQUIRE(std::memcmp(&out[(i * n + k) * w], tr.x[k].data(), w * sizeof(double)) == 0);
    }
  }
}

TEST_CASE("serial and TBB runs on 2 threads and on all cores give the same rows bit for bit, failures included") {
  // Gains and loads sampled from a seed; a few cases made to fail.
  auto cases = en::sample<2>({"kp", "m_load"}, {en::log_uniform(1, 100), en::uniform(0.05, 3.0)}, 150, 7);
  cases.cases[17][1] = -1.0;                                      // a negative mass: refused by the scene
  cases.cases[60][0] = std::numeric_limits<double>::quiet_NaN();  // a NaN gain: a NaN force
  auto study = en::make(crane_setup, 0.0, 4.0, {.tolerance = 1e-8},
                        en::maximum("max_swing", [](const auto& s, double t, const auto& x) { return swing(s, t, x); }),
                        en::settling_time("settle", [](const auto& s, double t, const auto& x) { return swing(s, t, x); },
                                          0.01),
                        en::final_state{});
  const en::run_options small_blocks{.block = 16};
  const auto serial = study.run(cases, en::serial{}, small_blocks);
  CHECK(serial.failed() == 2);
  require_identical(serial, study.run(cases, en::tbb_threads{2}, small_blocks));
  require_identical(serial, study.run(cases, en::tbb_threads{}));  // as many threads as cores
  REQUIRE(serial.outputs[0] == "max_swing");
  REQUIRE(serial.outputs[2] == "q0");
  REQUIRE(serial.outputs[5] == "v1");
}

TEST_CASE("a failing case is recorded with its reason, time and state, and the other cases go on") {
  auto cases = en::list<1>({"theta0"}, {{0.5}, {std::numeric_limits<double>::quiet_NaN()}, {1.0}, {-7.0}, {1.5}});
  // Case 3 asks for a negative rod mass: the scene refuses it at construction.
  auto study = en::make([](const std::array<double, 1>& c) {
    return std::pair{pendulum(1.0, c[0] < -5 ? -1.0 : 0.3), Pendulum::state_type{c[0], 0.0}};
  }, 0.0, 2.0, {}, en::final_value("theta", [](const auto&, double, const auto& x) { return x[0]; }));
  const auto res = study.run(cases);
  REQUIRE(res.failed() == 2);
  CHECK(res.rows[0].ok);
  CHECK(res.rows[2].ok);
  CHECK(res.rows[4].ok);
  // The NaN initial angle: checked() stops it at t0 with the state.
  CHECK_FALSE(res.rows[1].ok);
  CHECK(res.rows[1].reason.find("the state is not finite at t = 0") != std::string::npos);
  CHECK(res.rows[1].fail_time == 0.0);
  CHECK(std::isnan(res.rows[1].fail_state[0]));
  CHECK(std::isnan(res.rows[1].values[0]));
  // The negative mass: a parameter error, no time.
  CHECK_FALSE(res.rows[3].ok);
  CHECK(res.rows[3].reason.find("\"bob\": mass m = -1 is negative") != std::string::npos);
  CHECK(std::isnan(res.rows[3].fail_time));

  SECTION("a spent budget is the case's failure, with the time it was spent and the last accepted state") {
    auto tight = en::make([](const std::array<double, 1>& c) {
      return std::pair{pendulum(1.0, 0.3), Pendulum::state_type{c[0], 0.0}};
    }, 0.0, 2.0, {.max_rhs_evals = 60}, en::final_state{});
    const auto r = tight.run(en::list<1>({"phi0"}, {{0.5}}));
    REQUIRE(r.failed() == 1);
    CHECK(r.rows[0].reason.find("the budget of 60 derivative evaluations is spent") != std::string::npos);
    CHECK(r.rows[0].fail_time > 0.0);
    CHECK(std::isfinite(r.rows[0].fail_state[0]));
    CHECK(r.rows[0].rhs_evals == 61);
  }
  SECTION("the CSV has a header, one line a case, and the reason quoted") {
    std::ostringstream os;
    res.write_csv(os, cases);
    const std::string csv = os.str();
    CHECK(csv.rfind("case,theta0,ok,theta,rhs_evals,steps,fail_time,reason\n", 0) == 0);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 6);
    CHECK(csv.find("\n1,nan,0,nan,") != std::string::npos);
    CHECK(csv.find(",\"flange: the state is not finite at t = 0") != std::string::npos);
  }
}

TEST_CASE("cases: grids in order, seeded samples repeat and follow their distributions") {
  const auto g = en::grid<2>({"a", "b"}, {std::vector<double>{1, 2}, std::vector<double>{10, 20, 30}});
  REQUIRE(g.size() == 6);
  CHECK(g[0] == std::array<double, 2>{1, 10});
  CHECK(g[2] == std::array<double, 2>{1, 30});
  CHECK(g[3] == std::array<double, 2>{2, 10});
  const auto a = en::sample<2>({"u", "n"}, {en::uniform(2, 4), en::normal(5, 0.5)}, 20000, 123);
  const auto b = en::sample<2>({"u", "n"}, {en::uniform(2, 4), en::normal(5, 0.5)}, 20000, 123);
  CHECK(a.cases == b.cases);
  double mu = 0, mn = 0, vn = 0;
  for (const auto& c : a.cases) {
    REQUIRE(c[0] >= 2);
    REQUIRE(c[0] < 4);
    mu += c[0];
    mn += c[1];
  }
  mu /= 20000, mn /= 20000;
  for (const auto& c : a.cases) vn += (c[1] - mn) * (c[1] - mn);
  vn /= 19999;
  // Means within 5 standard errors; the normal's variance within 5 of its
  // standard errors (σ²·sqrt(2/n)).
  CHECK(std::abs(mu - 3) < 5 * (2 / std::sqrt(12.0)) / std::sqrt(20000.0));
  CHECK(std::abs(mn - 5) < 5 * 0.5 / std::sqrt(20000.0));
  CHECK(std::abs(vn - 0.25) < 5 * 0.25 * std::sqrt(2.0 / 20000));
  CHECK_THROWS_WITH(en::sample<1>({"x"}, {en::normal(0, -1)}, 1, 0),
                    Catch::Contains("the distribution of \"x\" has invalid bounds"));
}

TEST_CASE("the options are simulate's: checked as simulate checks them, and the earlier spec still runs") {
  const auto setup = [](const std::array<double, 1>& c) {
    return std::pair{pendulum(1.0, 0.3), Pendulum::state_type{c[0], 0.0}};
  };
  CHECK_THROWS_WITH(en::make(setup, 0.0, 1.0, {.tolerance = 1e-17}, en::final_state{}),
                    Catch::Matchers::Contains("ensemble") && Catch::Matchers::Contains("double precision"));
  CHECK_THROWS_WITH(en::make(setup, 0.0, 1.0, {.dt = 0}, en::final_state{}),
                    Catch::Matchers::Contains("dt = 0"));
  CHECK_THROWS_WITH(en::make(setup, 1.0, 1.0, {}, en::final_state{}), Catch::Matchers::Contains("t1 > t0"));
  // A relative tolerance of its own reaches the stepper: the case ends where
  // simulate ends with the same options.
  const simulate_options o{.tolerance = 1e-10, .rel_tolerance = 1e-6};
  const auto cases = en::list<1>({"phi0"}, {{0.5}});
  const auto r = en::make(setup, 0.0, 2.0, o, en::final_state{}).run(cases);
  auto [p, x0] = setup(cases[0]);
  const auto x = simulate(p, x0, 0.0, 2.0, o);
  const auto x_abs = simulate(p, x0, 0.0, 2.0, {.tolerance = 1e-10});
  CHECK(std::memcmp(&r.rows[0].values[0], &x[0], sizeof(double)) == 0);
  CHECK(x[0] != x_abs[0]);  // the relative tolerance took effect
  // ensemble::integration, the earlier spec (deprecated), maps onto the options.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  const auto old = en::make(setup, en::integration{.t1 = 2.0, .abs_tol = 1e-10, .rel_tol = 1e-6}, en::final_state{})
                       .run(cases);
#pragma GCC diagnostic pop
  CHECK(std::memcmp(&old.rows[0].values[0], &x[0], sizeof(double)) == 0);
}
