// Boost.Odeint steppers on flange scenes: each reaches a tight reference, the
// integrate functions drive observers that record recovered quantities, and
// the free arm conserves energy.
#include <vector>

#include <catch2/catch.hpp>
#include <flange/simulate/odeint.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

#include "random_params.hpp"

using namespace flange;
using Crane = decltype(models::gantry_crane());
using X = Crane::state_type;

namespace {
const models::gantry_crane_params P{.M = 2.0, .m = 0.7, .d = 1.2, .g = 9.81};
auto crane() {
  return models::gantry_crane(P, [](double t) { return 3.0 * std::sin(2.0 * t); });
}
const X x0{0.0, -0.4, 0.5, 0.0};
constexpr double T = 2.0;

X reference() {
  X x = x0;
  auto st = odeint::make_controlled(1e-14, 1e-14, odeint::runge_kutta_fehlberg78<X>());
  odeint::integrate_adaptive(st, crane(), x, 0.0, T, 1e-4);
  return x;
}
double distance(const X& a, const X& b) {
  double d = 0;
  for (int i = 0; i < 4; ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}
}  // namespace

TEST_CASE("every explicit stepper reaches the tight reference") {
  const auto s = crane();
  const X ref = reference();
  // Controlled steppers at tolerance 1e-10: the global error is the local
  // tolerance times the error growth over 2 s, well below 1e-7 here.
  SECTION("runge_kutta4, fixed step 1e-3: global error O(h⁴)") {
    X x = x0;
    odeint::integrate_const(odeint::runge_kutta4<X>(), s, x, 0.0, T, 1e-3);
    CHECK(distance(x, ref) < 1e-9);
  }
  SECTION("runge_kutta_cash_karp54, controlled") {
    X x = x0;
    odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_cash_karp54<X>()), s, x, 0.0,
                               T, 1e-3);
    CHECK(distance(x, ref) < 1e-7);
  }
  SECTION("runge_kutta_dopri5, controlled") {
    X x = x0;
    odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, T,
                               1e-3);
    CHECK(distance(x, ref) < 1e-7);
  }
  SECTION("runge_kutta_dopri5, dense output at fixed times") {
    X x = x0;
    std::vector<double> times;
    odeint::integrate_const(odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), s, x, 0.0, T,
                            0.25, [&](const X&, double t) { times.push_back(t); });
    CHECK(distance(x, ref) < 1e-7);
    CHECK(times.size() == 9);
  }
  SECTION("runge_kutta_fehlberg78, controlled") {
    X x = x0;
    odeint::integrate_adaptive(odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_fehlberg78<X>()), s, x, 0.0,
                               T, 1e-3);
    CHECK(distance(x, ref) < 1e-7);
  }
  SECTION("bulirsch_stoer") {
    X x = x0;
    odeint::bulirsch_stoer<X> bs(1e-10, 1e-10);
    odeint::integrate_adaptive(bs, s, x, 0.0, T, 1e-2);
    CHECK(distance(x, ref) < 1e-7);
  }
  SECTION("adams_bashforth_moulton, 5 steps, fixed step 1e-3") {
    X x = x0;
    odeint::integrate_const(odeint::adams_bashforth_moulton<5, X>(), s, x, 0.0, T, 1e-3);
    CHECK(distance(x, ref) < 1e-9);
  }
  SECTION("an Eigen state with vector_space_algebra") {
    eigen_state<Crane> x;
    x << x0[0], x0[1], x0[2], x0[3];
    using E = eigen_state<Crane>;
    odeint::integrate_const(odeint::runge_kutta4<E, double, E, double, odeint::vector_space_algebra>(), s, x, 0.0, T,
                            1e-3);
    CHECK(distance(X{x(0), x(1), x(2), x(3)}, ref) < 1e-9);
  }
}

TEST_CASE("integrate_times hands an observer every recovered quantity") {
  const auto s = crane();
  X x = x0;
  const std::vector<double> times{0.0, 0.5, 1.0, 1.5, 2.0};
  std::vector<double> seen, tension;
  odeint::integrate_times(odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), s, x,
                          times.begin(), times.end(), 0.01, record(s, [&](const auto& sol) {
                            seen.push_back(sol.t);
                            // The rope force on the load, from the load's cut force.
                            tension.push_back(sol.cut_at("load.frame_a").f.norm());
                          }));
  CHECK(seen == times);
  for (double f : tension) CHECK(f > 0);
}

TEST_CASE("the free robot arm conserves energy to 1e-9 over 100 s with dopri5 at 1e-12") {
  const auto arm = models::robot_arm();
  using A = decltype(arm)::state_type;
  A x{0.3, 0.0};
  const double e0 = recover(arm, 0.0, x).energy();
  double worst = 0;
  odeint::integrate_const(odeint::make_dense_output(1e-12, 1e-12, odeint::runge_kutta_dopri5<A>()), arm, x, 0.0,
                          100.0, 1.0, record(arm, [&](const auto& sol) {
                            worst = std::max(worst, std::abs(sol.energy() - e0) / std::abs(e0));
                          }));
  INFO("worst relative energy error " << worst);
  CHECK(worst < 1e-9);
}
