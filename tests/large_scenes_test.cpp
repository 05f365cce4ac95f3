// Scenes of robot size and beyond: a spatial chain of 64 links (run-time
// axes) and a floating tree of 32 joints (models::legged<4, 8>, 38 rates); built
// with -DFLANGE_LARGE_CHAIN=128 -DFLANGE_LARGE_LEGS=15, a chain of 128 links
// and a tree of 60 joints (66 rates), too costly to compile in every CI run
// (docs/performance.md, "Compile time at scale"; tools/large_scenes.sh).
// Both compile, both take the articulated-body algorithm by the cost model
// (dynamics/algorithm.hpp), and their accelerations are checked against two
// others built from Newton–Euler inverse dynamics (newton_euler.hpp):
// - at the computed v̇ it must give back the joints' forces, zero here, to
//   round-off of the bias forces it balances;
// - Newton–Euler with the mass matrix, the other forward algorithm, with M
//   built column by column from inverse dynamics (Walker and Orin's first
//   method; the library's own composite-rigid-body M is checked against the
//   articulated body on every random tree of tree_test and tree_joints_test,
//   but its unrolled N³ LDLᵀ is not built at this size).
// And the chain's derivative and a stepping loop of RK4 do not touch the
// heap (allocation_counter.cpp).
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/legged.hpp>
#include <Eigen/Dense>
#include <limits>
#include <random>

#include "allocation_counter.hpp"

using namespace flange;

namespace {

#ifndef FLANGE_LARGE_CHAIN
#define FLANGE_LARGE_CHAIN 64
#endif
#ifndef FLANGE_LARGE_LEGS
#define FLANGE_LARGE_LEGS 8
#endif
constexpr int chain_links = FLANGE_LARGE_CHAIN, leg_links = FLANGE_LARGE_LEGS;

auto long_chain() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 1.0), s(-1, 1);
  models::chain_params<chain_links> p;
  for (int i = 0; i < chain_links; ++i) {
    p.axis[i] = Vec3d(s(rng), s(rng), 1).normalized();
    p.d[i] = Vec3d(0.1 * u(rng), 0.01 * s(rng), 0.01 * s(rng));
    p.m[i] = u(rng);
    p.J[i] = Vec3d(0.05, 0.06, 0.07).asDiagonal() * 1e-2;
  }
  return models::chain<chain_links, models::runtime_axes>(p);
}

template <class S>
typename S::state_type random_state(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> s(-1, 1);
  typename S::state_type x;
  for (auto& v : x) v = s(rng);
  return x;
}

/// The articulated body's v̇ (the scene's derivative) against two algorithms
/// built from Newton–Euler inverse dynamics, ID(q, v, v̇), with τ = 0 and
/// h = ID(q, v, 0), the bias forces:
/// - residual: max |ID(q, v, v̇)| / max |h|, how far v̇ is from balancing
///   the bias forces, relative to them;
/// - error: Newton–Euler with the mass matrix, the forward algorithm the
///   cost model did not pick, built as in Walker and Orin's first method:
///   column i of M = ID(q, v, eᵢ) − h, v̇_M = M⁻¹·(τ − h) by a dense LDLᵀ
///   (Eigen's); max |v̇ − v̇_M| / max |v̇_M|, and rcond, the LDLᵀ's estimate
///   of M's reciprocal condition number.
///
/// The second reference is the less precise of the two: M's entries carry
/// the round-off of h, and solving with M multiplies it by M's condition
/// number, so its relative error is of order ε / rcond. (A probe with the
/// 64-link chain's derivative in long double: the articulated body's v̇
/// within 4e-15 of it, this reference within 1.4e-10, at rcond 1.6e-7 to
/// 3.3e-7.)
struct second_algorithms {
  double residual, error, rcond;
};
template <class S>
second_algorithms check_against_newton_euler(const S& scene, const typename S::state_type& x) {
  typename S::state_type dx{};
  scene(x, dx, 0.0);
  const double* q = x.data();
  const double* v = x.data() + S::n_q;
  const double* vd = dx.data() + S::n_q;
  std::array<double, S::n_v> a{};
  const auto h = inverse_dynamics(scene, 0.0, q, v, a.data());
  const auto tau = inverse_dynamics(scene, 0.0, q, v, vd);
  Eigen::MatrixXd M(S::n_v, S::n_v);
  Eigen::VectorXd rhs(S::n_v);
  double r = 0, scale = 0;
  for (int i = 0; i < S::n_v; ++i) {
    r = std::max(r, std::abs(tau[i]));
    scale = std::max(scale, std::abs(h[i]));
    a[i] = 1.0;
    const auto c = inverse_dynamics(scene, 0.0, q, v, a.data());
    a[i] = 0.0;
    for (int k = 0; k < S::n_v; ++k) M(k, i) = c[k] - h[k];
    rhs(i) = -h[i];
  }
  // M from differences is symmetric to round-off; LDLᵀ reads its lower half.
  const Eigen::LDLT<Eigen::MatrixXd> f(M);
  const Eigen::VectorXd ref = f.solve(rhs);
  const Eigen::VectorXd diff = Eigen::Map<const Eigen::VectorXd>(vd, S::n_v) - ref;
  return {r / scale, diff.cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff(), f.rcond()};
}

}  // namespace

TEST_CASE("a long spatial chain takes the articulated body and balances its inverse dynamics") {
  const auto c = long_chain();
  using S = std::remove_cvref_t<decltype(c)>;
  STATIC_REQUIRE(S::n_v == chain_links);
  STATIC_REQUIRE(algorithm_for<S>() == forward_algorithm::articulated_body);
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const auto m = check_against_newton_euler(c, random_state<S>(seed));
    INFO("seed " << seed << ": residual " << m.residual);
    CHECK(m.residual < 1e-12);  // round-off of sums over the links, n·ε ≈ 1e-14 (measured ≤ 3e-16)
    INFO("against Newton–Euler + M: " << m.error << ", rcond(M) " << m.rcond);
    // The reference's own error bound, ε·cond(M) (measured ≤ 0.14 of it, 64 and 128 links).
    CHECK(m.error < std::numeric_limits<double>::epsilon() / m.rcond);
  }
}

TEST_CASE("a long spatial chain steps under RK4 without the heap") {
  const auto c = long_chain();
  using S = std::remove_cvref_t<decltype(c)>;
  auto x = random_state<S>(4);
  boost::numeric::odeint::runge_kutta4<typename S::state_type> rk4;
  typename S::state_type dx{};
  CHECK(test::count_allocations([&] { c(x, dx, 0.0); }) == 0);
  double t = 0;
  const double dt = 1e-4;
  CHECK(test::count_allocations([&] {
          for (int k = 0; k < 20; ++k, t += dt) rk4.do_step(std::cref(c), x, t, dt);
        }) == 0);
  bool finite = true;
  for (const double xi : x) finite = finite && std::isfinite(xi);
  CHECK(finite);
}

TEST_CASE("a floating tree of four long legs takes the articulated body and balances its inverse dynamics") {
  const auto t = models::legged<4, leg_links>();
  using S = std::remove_cvref_t<decltype(t)>;
  STATIC_REQUIRE(S::n_v == 6 + 4 * leg_links);
  STATIC_REQUIRE(algorithm_for<S>() == forward_algorithm::articulated_body);
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    auto x = random_state<S>(seed);
    double n = 0;
    for (int i = 3; i < 7; ++i) n += x[i] * x[i];
    for (int i = 3; i < 7; ++i) x[i] /= std::sqrt(n);
    const auto m = check_against_newton_euler(t, x);
    INFO("seed " << seed << ": residual " << m.residual);
    CHECK(m.residual < 1e-12);  // round-off of sums over the links, n·ε ≈ 1e-14 (measured ≤ 3e-16)
    INFO("against Newton–Euler + M: " << m.error << ", rcond(M) " << m.rcond);
    CHECK(m.error < std::numeric_limits<double>::epsilon() / m.rcond);  // as for the chain
    CHECK(m.error < 1e-10);  // the bound: M is better conditioned here (rcond 1e-6 to 1e-5)
    typename S::state_type dx{};
    CHECK(test::count_allocations([&] { t(x, dx, 0.0); }) == 0);
  }
}
