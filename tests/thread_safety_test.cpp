// A scene is safe to evaluate from many threads at once: it is const after
// construction and holds no shared mutable state, and so is an ensemble
// study. Four std::threads share one scene (a spatial tree of every joint
// kind, a closed four-bar) and one ensemble study, and every result must
// equal the serial one bit for bit. tools/sanitizers.sh runs this file under
// ThreadSanitizer, which reports any data race between the threads (the TBB
// engine is left out there: Debian's libtbb is not instrumented, and TSan
// reports its scheduler's own synchronisation as races).
#include <catch2/catch.hpp>

#include <array>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

#include <flange/ensemble/ensemble.hpp>
#include <flange/ensemble/record.hpp>
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

#include "tree_laws.hpp"

using namespace flange;
namespace en = flange::ensemble;

namespace {

constexpr int n_threads = 4;

/// Runs f(k) on n_threads threads at once, k = 0 … n_threads − 1.
template <class F>
void on_threads(F f) {
  std::vector<std::thread> ts;
  for (int k = 0; k < n_threads; ++k) ts.emplace_back([&f, k] { f(k); });
  for (auto& t : ts) t.join();
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Everything a user computes from a scene at a state: the derivative,
/// recovered energy and cut forces, the residual, and a short checked
/// simulation.
template <class S>
std::vector<double> work(const S& s, const std::vector<typename S::state_type>& states, double t1) {
  std::vector<double> out;
  for (const auto& x : states) {
    typename S::state_type dx;
    s(x, dx, 0.3);
    out.insert(out.end(), dx.begin(), dx.end());
    const auto sol = recover(s, 0.3, x);
    out.push_back(sol.energy());
    for (const auto& w : sol.cut) out.insert(out.end(), {w.f[0], w.f[1], w.f[2], w.n[0], w.n[1], w.n[2]});
    out.push_back(scaled_residual(s, sol));
    const auto x1 = simulate(s, x, 0.0, t1, {.tolerance = 1e-9});
    out.insert(out.end(), x1.begin(), x1.end());
  }
  return out;
}

template <class S>
void check_shared_scene(const S& s, const std::vector<typename S::state_type>& states, double t1) {
  const auto serial = work(s, states, t1);
  std::array<std::vector<double>, n_threads> got;
  on_threads([&](int k) { got[k] = work(s, states, t1); });
  for (int k = 0; k < n_threads; ++k) {
    INFO("thread " << k);
    REQUIRE(same_bits(got[k], serial));
  }
}

/// A policy that spreads a block's cases over std::threads (what any
/// threading library does), so the study's own code runs concurrently.
struct std_threads {
  template <class F>
  void for_each(std::size_t n, F&& f) const {
    std::vector<std::thread> ts;
    for (int k = 0; k < n_threads; ++k)
      ts.emplace_back([&f, n, k] {
        for (std::size_t i = std::size_t(k); i < n; i += n_threads) f(i);
      });
    for (auto& t : ts) t.join();
  }
};

}  // namespace

TEST_CASE("one spatial tree of every joint kind, evaluated, recovered and simulated on four threads at once") {
  constexpr auto shape = models::random_tree_shape(7, 6, false, true);
  std::mt19937 rng(11);
  const auto s = models::tree<shape>(test::tree_params<shape.n>(rng));
  std::vector<std::remove_cvref_t<decltype(s)>::state_type> states;
  for (int i = 0; i < 4; ++i) states.push_back(test::random_state(s, rng));
  check_shared_scene(s, states, 0.05);
}

TEST_CASE("one closed four-bar (constraint solve and projection) on four threads at once") {
  const models::fourbar_params p;
  const auto fb = models::fourbar(p);
  std::vector<std::remove_cvref_t<decltype(fb)>::state_type> states;
  for (double th2 : {0.4, 1.3, 2.5}) {
    const auto q = models::fourbar_coordinates(p, th2, models::freudenstein_rocker(p, th2));
    auto x = initial_state<"crank_pivot", "crank_pin", "rocker_pin">(fb, {.q = q[0], .v = 1.5}, {.q = q[1]}, {.q = q[2]});
    close_loops<"crank_pivot">(fb, x);
    states.push_back(x);
  }
  check_shared_scene(fb, states, 0.2);
}

TEST_CASE("one ensemble study run from four threads at once, and its cases spread over four threads") {
  auto study = en::make(
      [](const std::array<double, 2>& c) {
        models::gantry_crane_params p;
        p.m = c[0];
        return std::pair{models::gantry_crane(p, 0.5), std::array<double, 4>{0, c[1], 0, 0}};
      },
      0.0, 2.0, {.tolerance = 1e-9, .dt = 1e-3},
      en::final_state{}, en::maximum("swing", [](const auto&, double, const auto& x) { return std::abs(x[1]); }));
  auto cases = en::grid<2>({"m", "theta0"}, {en::linspace(0.5, 3.0, 4), en::linspace(-1.0, 1.0, 4)});
  const auto serial = study.run(cases);
  REQUIRE(serial.failed() == 0);
  auto same = [&](const auto& r) {
    REQUIRE(r.rows.size() == serial.rows.size());
    for (std::size_t i = 0; i < r.rows.size(); ++i) {
      REQUIRE(r.rows[i].rhs_evals == serial.rows[i].rhs_evals);
      REQUIRE(std::memcmp(r.rows[i].values.data(), serial.rows[i].values.data(),
                          sizeof(double) * r.rows[i].values.size()) == 0);
    }
  };
  same(study.run(cases, std_threads{}));
  std::array<decltype(study.run(cases)), n_threads> got;
  on_threads([&](int k) { got[k] = study.run(cases); });
  for (const auto& r : got) same(r);
}
