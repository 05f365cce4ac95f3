// The exact Jacobian from dual numbers against central finite differences, and
// rosenbrock4 driven by it.
#include <catch2/catch.hpp>

#include <limits>
#include <random>
#include <string>

#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>
#include <flange/simulate/rosenbrock4.hpp>
#include <flange/simulate/odeint.hpp>

#include "random_params.hpp"

using namespace flange;

namespace {
/// Central differences of the derivative in x (and t). With h = 1e-6 the
/// truncation error is O(h²·f''') ≈ 1e-12 and the rounding O(ε·|f|/h) ≈ 1e-10
/// relative, so agreement to 1e-7 relative to the entries' scale is a fair bar.
template <class S, std::size_t N>
void check_jacobian(const S& scene, double t, const std::array<double, N>& x) {
  Eigen::Matrix<double, N, 1> ft;
  const auto J = jacobian(scene, t, x, &ft);
  const double h = 1e-6;
  double scale = 1;
  for (int i = 0; i < int(N); ++i)
    for (int k = 0; k < int(N); ++k) scale = std::max(scale, std::abs(J(i, k)));
  // The library's own central differences (h = ε^(1/3)·max(1, |x|), the
  // step rosenbrock4's finite-difference option uses) meet the same bar.
  Eigen::Matrix<double, N, 1> ft_fd;
  const auto J_fd = jacobian_finite_difference(scene, t, x, &ft_fd);
  CHECK((J_fd - J).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  CHECK((ft_fd - ft).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  for (int k = 0; k <= int(N); ++k) {
    auto xp = x, xm = x;
    double tp = t, tm = t;
    if (k < int(N)) {
      xp[k] += h;
      xm[k] -= h;
    } else {
      tp += h;
      tm -= h;
    }
    std::array<double, N> fp, fm;
    scene(xp, fp, tp);
    scene(xm, fm, tm);
    for (int i = 0; i < int(N); ++i) {
      const double fd = (fp[i] - fm[i]) / (2 * h), exact = k < int(N) ? J(i, k) : ft(i);
      INFO("row " << i << ", column " << k << " (" << N << " = ∂/∂t)");
      CHECK(std::abs(exact - fd) <= 1e-7 * scale);
    }
  }
}
}  // namespace

TEST_CASE("the dual-number Jacobian matches finite differences") {
  std::mt19937 rng(21);
  SECTION("robot arm under a generic PD law") {
    auto pd = [](auto t, const auto& x) {
      using std::sin;
      return Eigen::Matrix<std::remove_cvref_t<decltype(t)>, 3, 1>(0, 0, -8.0 * (x.q(0) - sin(t)) - 1.5 * x.v(0));
    };
    const auto arm = models::robot_arm(test::arm_params(rng), pd);
    for (int k = 0; k < 10; ++k)
      check_jacobian(arm, test::uniform(rng, 0, 5), std::array<double, 2>{test::uniform(rng, -3, 3), test::uniform(rng, -3, 3)});
  }
  SECTION("gantry crane under a time-varying force") {
    const auto crane = models::gantry_crane(test::crane_params(rng), [](auto t) {
      using std::sin;
      return 3.0 * sin(2.0 * t);
    });
    for (int k = 0; k < 10; ++k) {
      std::array<double, 4> x;
      for (auto& v : x) v = test::uniform(rng, -2, 2);
      check_jacobian(crane, test::uniform(rng, 0, 5), x);
    }
  }
  SECTION("spatial chain of 4 links") {
    const auto chain = models::chain<4, models::runtime_axes>(test::chain_params<4>(rng));
    for (int k = 0; k < 5; ++k) {
      std::array<double, 8> x;
      for (auto& v : x) v = test::uniform(rng, -2, 2);
      check_jacobian(chain, 0.0, x);
    }
  }
  SECTION("a row of 8 loop windows: the solves over M's and B's nonzeros") {
    // 17 rates, M block-diagonal: the sparse factor and the QR's row
    // tracking (loop_solve.hpp) run on dual numbers. On the loops at θ, the
    // row has one degree of freedom with J·θ̈ = −C·cos θ (J and C from the
    // masses, see models::window_row): along the loops' tangent (every post
    // +δ, every top pin −δ) the Jacobian gives ∂θ̈/∂θ = C·sin θ / J, and
    // along the same direction in the rates 0 (θ̈ does not depend on θ̇).
    const models::window_row_params p{};
    const auto row = models::window_row<8>(p);
    using S = decltype(row);
    constexpr int n = S::n_q + S::n_v;
    const double th = 1.2;
    S::state_type x{};
    std::array<double, n> tangent{};
    for (int i = 0; i <= 8; ++i) {
      const int k = S::q_offset("post_pivot" + std::to_string(i));
      x[k] = th;
      x[S::n_q + k] = 0.7;
      tangent[k] = 1;
    }
    for (int i = 0; i < 8; ++i) {
      const int k = S::q_offset("top_pin" + std::to_string(i));
      x[k] = -th;
      x[S::n_q + k] = -0.7;
      tangent[k] = -1;
    }
    close_loops<"post_pivot0">(row, x);
    const double h = p.height, g = -p.g.y(), J = 9 * p.m_post * h * h / 3 + 8 * p.m_top * h * h;
    const double C = (9 * p.m_post * h / 2 + 8 * p.m_top * h) * g;
    const auto Jx = jacobian(row, 0.0, x);
    const Eigen::Matrix<double, n, 1> t = Eigen::Map<const Eigen::Matrix<double, n, 1>>(tangent.data());
    Eigen::Matrix<double, n, 1> tv = Eigen::Matrix<double, n, 1>::Zero();
    tv.tail<S::n_v>() = t.head<S::n_q>();
    const Eigen::Matrix<double, n, 1> along_q = Jx * t, along_v = Jx * tv;
    const double expect = C * std::sin(th) / J;  // 11.1 s⁻²
    for (int i = 0; i < S::n_v; ++i) {
      INFO("rate " << i);
      // the solves' round-off, a few ε times the Jacobian's entries (at most
      // 12.5 here): measured 1.2e-14 and 1.1e-15
      CHECK(std::abs(along_q(S::n_q + i) - t(i) * expect) <= 1e-12);
      CHECK(std::abs(along_v(S::n_q + i)) <= 1e-12);
      CHECK(along_q(i) == 0.0);  // q̇ = v does not depend on q
      CHECK(along_v(i) == t(i));
    }
    // Off the loops (by up to 1e-3), against central differences.
    for (int k = 0; k < 3; ++k) {
      auto y = x;
      for (int i = 0; i < S::n_q; ++i) y[i] += test::uniform(rng, -1e-3, 1e-3);
      for (int i = S::n_q; i < n; ++i) y[i] = test::uniform(rng, -1, 1);
      check_jacobian(row, 0.0, y);
    }
  }
  SECTION("branched spatial tree with every joint and force element") {
    constexpr auto shape = models::random_tree_shape(3, 8, false);
    const auto tree = models::tree<shape>(test::tree_params<shape.n>(rng));
    for (int k = 0; k < 5; ++k) {
      decltype(tree)::state_type x;
      for (auto& v : x) v = test::uniform(rng, -1, 1);
      check_jacobian(tree, 0.0, x);
    }
  }
}

namespace {
/// jacobian() of a scene with loops, where its loop solve is exact, against
/// jacobian_dual(), which carries the dual numbers through the mass matrix,
/// its factor and the loop solve: the same derivative by another algorithm,
/// to round-off (the solves' few ε of the entries: 1e-12 of the largest).
template <class S, std::size_t N>
void check_implicit(const S& scene, double t, const std::array<double, N>& x) {
  jacobian_matrix<S> J;
  Eigen::Matrix<double, N, 1> ft, ft_d;
  REQUIRE(detail::jacobian_loops(scene, t, x, J, &ft));  // the implicit path, not dual numbers
  const auto Jd = jacobian_dual(scene, t, x, &ft_d);
  const double scale = std::max(1.0, Jd.cwiseAbs().maxCoeff());
  CHECK((J - Jd).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((ft - ft_d).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK((jacobian(scene, t, x) - J).cwiseAbs().maxCoeff() == 0.0);  // jacobian() takes it
}
}  // namespace

TEST_CASE("with loops, the Jacobian by implicit differentiation equals dual numbers") {
  std::mt19937 rng(5);
  SECTION("four-bar and slider-crank, on their loops and off them") {
    const models::fourbar_params p{};
    const auto fb = models::fourbar(p);
    const auto sc = models::slider_crank(models::slider_crank_params{});
    for (int k = 0; k < 6; ++k) {
      const double th = test::uniform(rng, 0, 6.28);
      const auto q = models::fourbar_coordinates(p, th, models::freudenstein_rocker(p, th));
      std::array<double, 6> x{q[0], q[1], q[2], test::uniform(rng, -3, 3), test::uniform(rng, -3, 3),
                              test::uniform(rng, -3, 3)};
      close_loops<"crank_pivot">(fb, x);
      check_implicit(fb, 0.3, x);
      for (int i = 0; i < 3; ++i) x[i] += test::uniform(rng, -1e-3, 1e-3);  // off the loop
      check_implicit(fb, 0.3, x);
      std::array<double, 6> y{th, test::uniform(rng, -1, 1), test::uniform(rng, 0.3, 0.4), test::uniform(rng, -3, 3),
                              test::uniform(rng, -3, 3), test::uniform(rng, -3, 3)};
      close_loops<"crank_pivot">(sc, y);
      check_implicit(sc, 1.1, y);
    }
  }
  SECTION("a row of loop windows in space repeats its constraints: dual numbers") {
    // Run-time axes make every window's cut a spatial revolute (5 rows), of
    // which the row's plane repeats 3: the loop solve leaves rows out, and
    // jacobian() takes dual numbers, rows left out included.
    const auto row = models::window_row<2, models::window_row_params, axis::any>(models::window_row_params{});
    using S = decltype(row);
    S::state_type x{};
    for (int i = 0; i <= 2; ++i) {
      const int k = S::q_offset("post_pivot" + std::to_string(i));
      x[k] = 1.2;
      x[S::n_q + k] = 0.7;
    }
    for (int i = 0; i < 2; ++i) {
      const int k = S::q_offset("top_pin" + std::to_string(i));
      x[k] = -1.2;
      x[S::n_q + k] = -0.7;
    }
    close_loops<"post_pivot0">(row, x);
    jacobian_matrix<S> J;
    CHECK_FALSE(detail::jacobian_loops(row, 0.0, x, J));
    CHECK((jacobian(row, 0.0, x) - jacobian_dual(row, 0.0, x)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("a dual number is exactly zero only with its derivatives") {
  // The loop solve skips products with exact zeros (loop_solve.hpp); a
  // coefficient whose value vanishes at this state but not its derivative
  // (sin θ at θ = 0) must not be skipped.
  using D = dual<double, 2>;
  CHECK(exactly_zero(D(0.0)));
  CHECK_FALSE(exactly_zero(D::variable(0.0, 1)));
  CHECK_FALSE(exactly_zero(D(1e-300)));
  CHECK(exactly_zero(0.0));
  CHECK(exactly_zero(-0.0));
  CHECK_FALSE(exactly_zero(std::numeric_limits<double>::denorm_min()));
}

TEST_CASE("a dual number's operators with a constant give what the constant as a dual gives") {
  // dual ± c, c − dual, dual · c and dual / c skip the constant's zero
  // derivatives; with finite operands the numbers are those of dual(c) but
  // for the sign of a zero (compared with ==, which does not see it).
  using D = dual<double, 3>;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  auto random_dual = [&] {
    D x(u(rng));
    for (auto& e : x.d) e = u(rng);
    x.d[1] = 0;  // a zero derivative, where a sign could differ
    return x;
  };
  auto same = [](const D& x, const D& y) {
    bool eq = x.v == y.v;
    for (int k = 0; k < 3; ++k) eq = eq && x.d[k] == y.d[k];
    return eq;
  };
  for (int i = 0; i < 100; ++i) {
    const D a = random_dual(), b = random_dual();
    const double c = u(rng) + 3;  // away from 0, for the division
    CHECK(same(a + c, a + D(c)));
    CHECK(same(c + a, D(c) + a));
    CHECK(same(a - c, a - D(c)));
    CHECK(same(c - a, D(c) - a));
    CHECK(same(a * c, a * D(c)));
    CHECK(same(c * a, D(c) * a));
    CHECK(same(a / c, a / D(c)));
    CHECK(same(-a, D(0.0) - a));
    // and the dual-dual operators as their compound forms
    D s = a;
    s *= b;
    CHECK(same(a * b, s));
    s = a;
    s /= b + D(5.0);
    CHECK(same(a / (b + D(5.0)), s));
  }
}

TEST_CASE("rosenbrock4 with the exact Jacobian converges to the tight reference") {
  const auto crane = models::gantry_crane({.M = 2.0, .m = 0.7, .d = 1.2}, [](auto t) {
    using std::sin;
    return 3.0 * sin(2.0 * t);
  });
  using X = decltype(crane)::state_type;
  X ref{0.0, -0.4, 0.5, 0.0};
  odeint::integrate_adaptive(odeint::make_controlled(1e-14, 1e-14, odeint::runge_kutta_fehlberg78<X>()), crane, ref,
                             0.0, 2.0, 1e-4);
  auto run = [&](double tol, int* observed) {
    X x{0.0, -0.4, 0.5, 0.0};
    const std::size_t steps = integrate_rosenbrock4(
        crane, x, 0.0, 2.0, 1e-3, tol, tol, [&](const X&, double) { ++*observed; }, 0.5);
    double err = 0;
    for (int i = 0; i < 4; ++i) err = std::max(err, std::abs(x[i] - ref[i]));
    return std::pair{steps, err};
  };
  int observed = 0;
  const auto [steps8, err8] = run(1e-8, &observed);
  CHECK(observed == 5);
  const auto [steps10, err10] = run(1e-10, &observed);
  INFO("tol 1e-8: " << steps8 << " steps, error " << err8 << "; tol 1e-10: " << steps10 << " steps, error " << err10);
  // rosenbrock4 controls the local error of each step to the tolerance; the
  // global error is at most their sum (steps × tol) for this non-stiff,
  // non-chaotic run over 2 s. It is order 4 here (time is a state, see
  // rosenbrock4.hpp): 100× tighter tolerance costs about 100^(1/4) ≈ 3× the
  // steps and cuts the error by far more than 10×. Without the repair the
  // steps grow 10× and the error falls only 10× (first order).
  // With central differences for the Jacobian it still converges: the
  // differences' 1e-10 error is far below what the tolerances ask.
  X xf{0.0, -0.4, 0.5, 0.0};
  stiff_stats st;
  integrate_rosenbrock4<jacobian_method::finite_difference>(crane, xf, 0.0, 2.0, 1e-3, 1e-8, 1e-8, nullptr, 0.0, &st);
  double err_fd = 0;
  for (int i = 0; i < 4; ++i) err_fd = std::max(err_fd, std::abs(xf[i] - ref[i]));
  INFO("finite-difference Jacobian at tol 1e-8: " << st.steps << " steps, error " << err_fd);
  CHECK(err_fd < double(st.steps) * 1e-8);
  CHECK(err8 < steps8 * 1e-8);
  CHECK(err10 < steps10 * 1e-10);
  CHECK(err10 < err8 / 30);
  CHECK(steps10 < 5 * steps8);
}

TEST_CASE("an error inside the derivative comes back through rosenbrock4") {
  const auto arm = models::robot_arm({.m = 0.0, .d = 0.5, .Jx = 0.0, .Jz = 0.0});
  std::array<double, 2> x{0.1, 0.0};
  CHECK_THROWS_AS(integrate_rosenbrock4(arm, x, 0.0, 1.0, 1e-3, 1e-8, 1e-8), simulation_error);
}
