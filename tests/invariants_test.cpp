// A law over the ways to integrate × the kinds of scene with invariants:
// every path flange offers (simulate with dopri5 and Bulirsch–Stoer,
// integrate_projected with a controlled and a fixed-step stepper, the
// ensembles with each method on each engine but MPI, which
// ensemble_mpi_test covers, integrate_rosenbrock4) ends a long run at a loose tolerance with its loops
// closed (|Φ|, |G·v| ≤ 1e-10) and its quaternions unit (|‖q‖ − 1| ≤ 1e-12),
// on a four-bar, a spatial loop, a free body and a top; an ensemble case's
// final state is simulate()'s bit for bit with the same method (and
// integrate_rosenbrock4's with rosenbrock4); and the raw Odeint path, which
// cannot project, reports the drift through `checked` instead of going on.
//
// The bounds are the projection's: after every step the state is moved back
// onto Φ = 0 to 8 ulp of the scene's size and onto G·v = 0 to round-off, and
// a quaternion is divided by its norm (a few ulp). Without the projection the
// same runs end 1e-5 … 1e-1 off (the tolerance's error, accumulated).
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include <flange/ensemble/ensemble.hpp>
#ifdef FLANGE_TEST_TBB
#include <flange/ensemble/tbb.hpp>
#endif
#include <flange/simulate/rosenbrock4.hpp>
#include <flange/simulate/bulirsch_stoer.hpp>

#include "invariant_scenes.hpp"

using namespace flange;
using namespace invariant_scenes;
namespace en = flange::ensemble;

namespace {

constexpr double tol = 1e-6;  // loose: the drift a path does not undo grows with it

/// A scene, its start, how long it runs, and where its quaternions are.
template <class S>
struct scene_case {
  std::string name;
  S scene;
  typename S::state_type x0;
  double t1;
  std::vector<int> quaternions;  // offsets in x of each quaternion
};

auto fourbar_case() {
  auto s = fourbar();
  return scene_case<Fourbar>{"four-bar", s, fourbar_start(s), 200.0, {}};
}
auto rsur_case() {
  auto c = rsur_closed();
  return scene_case<Rsur>{"spatial RSUR loop", c.scene, c.x, 50.0, {Rsur::q_offset("ball")}};
}
auto free_body_case() {
  auto s = free_body();
  return scene_case<FreeBody>{"free body", s, free_body_start(s), 100.0, {FreeBody::q_offset("fly") + 3}};
}
auto top_case() {
  auto s = top();
  return scene_case<Top>{"top", s, top_start(s), 20.0, {Top::q_offset("pivot")}};
}

template <class S>
void require_invariants(const scene_case<S>& c, const typename S::state_type& x, const std::string& path) {
  INFO(c.name << " through " << path);
  const auto r = loop_residual(c.scene, x);
  double q = 0;
  for (int at : c.quaternions) q = std::max(q, quaternion_error(x, at));
  INFO("|Φ| = " << r.max_phi() << ", |G·v| = " << r.max_phid() << ", |‖q‖ − 1| = " << q);
  CHECK(r.max_phi() <= 1e-10);
  CHECK(r.max_phid() <= 1e-10);
  CHECK(q <= 1e-12);
}

/// The final state of a one-case ensemble of the scene, run by `policy`.
template <class Method, class S, class Policy>
typename S::state_type ensemble_final(const scene_case<S>& c, const Policy& policy) {
  auto study = en::make_with<Method>([&](const std::array<double, 1>&) { return std::pair{c.scene, c.x0}; },
                                     0.0, c.t1, {.tolerance = tol, .dt = 1e-3},
                                     en::final_state{});
  const auto res = study.run(en::list<1>({"one"}, {{0.0}}), policy,
                             {.progress_line = en::run_options::show::never});
  INFO(c.name << ": " << res.rows[0].reason);
  REQUIRE(res.rows[0].ok);
  typename S::state_type x;
  for (int i = 0; i < S::n_state; ++i) x[i] = res.rows[0].values[i];
  return x;
}

template <class S>
void every_path(const scene_case<S>& c) {
  using X = typename S::state_type;
  const X by_simulate = simulate(c.scene, c.x0, 0.0, c.t1, {.tolerance = tol});
  require_invariants(c, by_simulate, "simulate (dopri5)");

  X x = c.x0;
  integrate_projected(odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<X>()), c.scene, x, 0.0, c.t1,
                      1e-3);
  require_invariants(c, x, "integrate_projected (controlled dopri5)");

  x = c.x0;
  integrate_projected(odeint::runge_kutta4<X>(), c.scene, x, 0.0, c.t1, 1e-3);
  require_invariants(c, x, "integrate_projected (rk4, dt = 1e-3)");

  const X by_ensemble = ensemble_final<en::method::dopri5>(c, en::serial{});
  require_invariants(c, by_ensemble, "a serial ensemble (dopri5)");
  {
    INFO(c.name << ": the ensemble's case and simulate() run the same method and must agree bit for bit");
    CHECK(std::memcmp(by_ensemble.data(), by_simulate.data(), sizeof(X)) == 0);
  }
  const X bs_ensemble = ensemble_final<en::method::bulirsch_stoer>(c, en::serial{});
  require_invariants(c, bs_ensemble, "a serial ensemble (Bulirsch–Stoer)");
  const X bs_simulate = simulate<method::bulirsch_stoer>(c.scene, c.x0, 0.0, c.t1, {.tolerance = tol});
  require_invariants(c, bs_simulate, "simulate (Bulirsch–Stoer)");
  CHECK(std::memcmp(bs_ensemble.data(), bs_simulate.data(), sizeof(X)) == 0);
#ifdef FLANGE_TEST_TBB
  const X by_threads = ensemble_final<en::method::dopri5>(c, en::tbb_threads{2});
  require_invariants(c, by_threads, "an ensemble on oneTBB threads (dopri5)");
  CHECK(std::memcmp(by_threads.data(), by_simulate.data(), sizeof(X)) == 0);
#endif

  x = c.x0;
  integrate_rosenbrock4(c.scene, x, 0.0, c.t1, 1e-3, tol, tol);
  require_invariants(c, x, "integrate_rosenbrock4");
  const X stiff_ensemble = ensemble_final<method::rosenbrock4>(c, en::serial{});
  require_invariants(c, stiff_ensemble, "a serial ensemble (rosenbrock4)");
  CHECK(std::memcmp(stiff_ensemble.data(), x.data(), sizeof(X)) == 0);  // the same loop and arithmetic
}

}  // namespace

TEST_CASE("every way to integrate keeps a four-bar's loop closed over 200 s at tolerance 1e-6") {
  every_path(fourbar_case());
}

TEST_CASE("every way to integrate keeps a spatial loop with a ball joint closed and its quaternion unit") {
  every_path(rsur_case());
}

TEST_CASE("every way to integrate keeps a free body's quaternion unit over 100 s") {
  every_path(free_body_case());
}

TEST_CASE("every way to integrate keeps a spinning top's quaternion unit") {
  every_path(top_case());
}

TEST_CASE("the raw Odeint path through checked reports a loop that drifts open instead of going on") {
  const auto c = fourbar_case();
  auto x = c.x0;
  auto stepper = odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<Fourbar::state_type>());
  budget b;  // the default drift bound
  try {
    odeint::integrate_adaptive(stepper, checked(c.scene, b), x, 0.0, c.t1, 1e-3);
    FAIL("the loop drifted open by " << loop_residual(c.scene, x).max_phi() << " m and checked said nothing");
  } catch (const simulation_error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("drifted off") != std::string::npos);
    CHECK(what.find("crank_pivot") == std::string::npos);  // it names the loop by its cut joint
    CHECK(what.find("rocker_pivot") != std::string::npos);
    CHECK(e.time > 0);
    CHECK(e.time < c.t1);
  }
}

TEST_CASE("the raw Odeint path through checked reports a quaternion that drifts off unit norm") {
  const auto c = free_body_case();
  auto x = c.x0;
  auto stepper = odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<FreeBody::state_type>());
  budget b{.max_drift = 1e-8};
  try {
    odeint::integrate_adaptive(stepper, checked(c.scene, b), x, 0.0, c.t1, 1e-3);
    FAIL("the quaternion drifted to |‖q‖ − 1| = " << quaternion_error(x, 3) << " and checked said nothing");
  } catch (const simulation_error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("drifted off") != std::string::npos);
    CHECK(what.find("\"fly\"") != std::string::npos);
  }
}

namespace {
/// A method whose stepper derails: after its fifth step the four-bar is
/// thrown into a stretched position (every joint at zero: the links in a
/// line, 1.1 m too long for the ground), from which no projection closes
/// the loop again.
struct derailing {
  template <class X, class S>
  static auto stepping(const S& scene, double abs_tol, double rel_tol) {
    return stepping_of<decltype(detail::method_stepping<method::dopri5, X>(scene, abs_tol, rel_tol)), X>{
        detail::method_stepping<method::dopri5, X>(scene, abs_tol, rel_tol)};
  }
  template <class Inner, class X>
  struct stepping_of : Inner {
    int steps = 0;
    template <class System>
    void step(System& sys, double t1) {
      Inner::step(sys, t1);
      if (++steps == 5) Inner::restart(X{});
    }
  };
};
}  // namespace

TEST_CASE("a case whose loop cannot be closed again fails with the loop, the time and the state") {
  const auto c = fourbar_case();
  try {
    (void)simulate<derailing>(c.scene, c.x0, 0.0, 1.0);
    FAIL("the loop was left open and simulate went on");
  } catch (const simulation_error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("the loop closed by Revolute \"rocker_pivot\" could not be closed again") != std::string::npos);
    CHECK(what.find("x = [0, 0, 0, 0, 0, 0]") != std::string::npos);
    CHECK(e.time > 0);
  }
  auto study = en::make_with<derailing>([&](const std::array<double, 1>&) { return std::pair{c.scene, c.x0}; },
                                        0.0, 1.0, {}, en::final_state{});
  const auto res = study.run(en::list<1>({"one"}, {{0.0}}), en::serial{}, {.progress_line = en::run_options::show::never});
  const auto& row = res.rows[0];
  INFO(row.reason);
  CHECK_FALSE(row.ok);
  CHECK(row.reason.find("could not be closed again") != std::string::npos);
  CHECK(row.fail_time > 0);
  // the last accepted state, the fourth step's end: on the loop
  typename Fourbar::state_type last;
  for (int i = 0; i < Fourbar::n_state; ++i) last[i] = row.fail_state[i];
  CHECK(loop_residual(c.scene, last).max_phi() <= 1e-10);
}
