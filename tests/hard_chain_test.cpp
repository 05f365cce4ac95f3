// Hard cases for chains: a link of almost no mass or inertia, against the
// same chain with a massless link, and a 16-link chaotic chain against a
// long-double solve.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <flange/flange.hpp>

#include "consistency.hpp"
#include "tree_laws.hpp"

using namespace flange;

namespace {
/// A spatial chain of 4 links on skew run-time axes whose second link has
/// mass m1 and inertia scaled to it (the others are of order one).
auto light_link_chain(double m1) {
  std::mt19937 rng(21);
  auto p = test::chain_params<4>(rng);
  p.J[1] *= m1 / p.m[1];
  p.m[1] = m1;
  return models::chain<4, models::runtime_axes>(p);
}
}  // namespace

TEST_CASE("links of almost no mass (1e-10 kg, inertia 1e-12 kg·m²) keep the laws and move as massless links") {
  // A link of 1e-10 kg between two joints is not singular: the joints behind
  // it move real mass. It must give what a link of exactly zero mass gives,
  // up to the mass it has: q̈ differs by about m/M ≈ 1e-10 relative, and so
  // does a 2 s trajectory (within its own integration error, 1e-12).
  const auto light = light_link_chain(1e-10);
  const auto none = light_link_chain(0.0);
  std::mt19937 rng(4);
  test::law_errors e;
  test::check_laws(light, rng, e, 20);
  INFO("NE − ABA " << e.algorithms << ", residual " << e.residual << ", power " << e.power);
  CHECK(e.algorithms <= 1e-10);
  CHECK(e.residual <= 1e-12);
  CHECK(e.power <= 1e-10);
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    const auto x = test::random_state(light, rng);
    std::array<double, 8> a, b;
    light(x, a, 0.0);
    none(x, b, 0.0);
    double scale = 1;
    for (int i = 4; i < 8; ++i) scale = std::max(scale, std::abs(b[i]));
    for (int i = 4; i < 8; ++i) worst = std::max(worst, std::abs(a[i] - b[i]) / scale);
  }
  INFO("largest relative q̈ difference, 1e-10 kg against massless: " << worst);
  CHECK(worst <= 1e-8);  // m/M = 1e-10 times the lever arms' ratios (≤ 1e2)
  // Over 0.5 s that q̈ difference moves the state by ½·δq̈·T² ≈ 2e-10 (|q̈|
  // of order 10 rad/s²); the bound allows ten times that for the growth of
  // the difference along the motion.
  std::array<double, 8> x0{0.3, -0.5, 0.8, 0.2, 0.5, 0.0, -0.4, 0.3};
  const auto xa = simulate(light, x0, 0.0, 0.5, {.tolerance = 1e-13});
  const auto xb = simulate(none, x0, 0.0, 0.5, {.tolerance = 1e-13});
  double dx = 0;
  for (int i = 0; i < 8; ++i) dx = std::max(dx, std::abs(xa[i] - xb[i]));
  WARN("near-massless link: q̈ differs by " << worst << " relative; after 0.5 s the states differ by " << dx);
  CHECK(dx <= 2e-9);
}

TEST_CASE("a 16-link chaotic chain conserves energy over 10 s and follows a long-double solve to a justified horizon") {
  // A planar chain of 16 links released from a bent, raised pose: chaotic.
  // The double solve (dopri5 at 1e-13) must keep its energy to 1e-10
  // relative, the bar of the double pendulum (measured 1.6e-12), and stay
  // within 1e-3 rad of a long-double solve (dopri5 at 1e-18) until errors of
  // 1e-13 have grown by e^{λt} to 1e-3; the horizon is measured and required
  // to be at least 1 s (λ of a long chain is larger than a double pendulum's).
  constexpr int N = 16;
  models::chain_params<N> p;
  for (int i = 0; i < N; ++i) {
    p.axis[i] = Vec3d::UnitZ();
    p.d[i] = Vec3d(0.1, 0, 0);
    p.m[i] = 0.2;
    p.J[i] = Vec3d(1e-4, 2e-4, 2e-4).asDiagonal();
  }
  const auto c = models::chain<N, models::planar_axes>(p);
  using X = decltype(c)::state_type;
  using L = std::array<long double, 2 * N>;
  X x{};
  L xl{};
  for (int i = 0; i < N; ++i) x[i] = xl[i] = (i == 0 ? 2.0 : 0.2 * std::sin(0.7 * i));
  const double e0 = recover(c, 0.0, x).energy();
  auto st = odeint::make_dense_output(1e-13, 1e-13, odeint::runge_kutta_dopri5<X>());
  auto stl = odeint::make_dense_output<odeint::runge_kutta_dopri5<L, long double>>(1e-18L, 1e-18L);
  st.initialize(x, 0.0, 1e-4);
  stl.initialize(xl, 0.0L, 1e-4L);
  double worst_energy = 0, first_divergence = -1;
  test::consistency cs;
  for (int k = 1; k <= 1000; ++k) {  // every 10 ms for 10 s
    const double t = 0.01 * k;
    while (st.current_time() < t) st.do_step(c);
    st.calc_state(t, x);
    if (first_divergence < 0) {
      while (stl.current_time() < t) stl.do_step(c);
      stl.calc_state(t, xl);
      double diff = 0;
      for (int i = 0; i < N; ++i) diff = std::max(diff, std::abs(x[i] - static_cast<double>(xl[i])));
      if (diff > 1e-3) first_divergence = t;
    }
    worst_energy = std::max(worst_energy, std::abs(recover(c, t, x).energy() - e0) / std::abs(e0));
    if (k % 100 == 0) cs.sample(c, t, x);
  }
  WARN("16-link chain: worst relative energy error " << worst_energy << " over 10 s; leaves the long-double solve at t = "
                                                     << first_divergence);
  CHECK(worst_energy <= 1e-10);
  CHECK(cs.residual <= 1e-9);
  CHECK(cs.algorithms <= 1e-10);
  CHECK((first_divergence < 0 || first_divergence >= 1.0));
}
