// The constrained solve of many loops (dynamics/loop_solve.hpp): from 16
// rates on, where M's factor is sparse, R comes from Givens rotations of B's
// rows in the constraints' order (dynamics/sparse_qr.hpp) and the
// projection's G·Gᵀ the same way. A row of 8 parallelogram windows
// (models::window_row, 17 rates) has one coordinate, so every post follows
// J·θ̈ = −V'(θ): checked through the flat positions, where every loop is
// singular at once (the damped solve), and written with run-time axes, where
// 24 of its 40 rows repeat others (the rows left out).
#include <boost/numeric/odeint.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>

using namespace flange;

namespace {

constexpr int windows = 8;

/// Every post at th, every top bar level: the row's one coordinate.
template <class S>
typename S::state_type at_angle(const S& s, double th) {
  typename S::state_type x{};
  for (int i = 0; i <= windows; ++i) x[S::q_offset("post_pivot" + std::to_string(i))] = th;
  for (int i = 0; i < windows; ++i) x[S::q_offset("top_pin" + std::to_string(i))] = -th;
  close_loops<"post_pivot0">(s, x);
  return x;
}

/// The worst difference of every post's angle from the one-coordinate
/// equation J·θ̈ = −C·cos θ (J = (N+1)·m_p·h²/3 + N·m_t·h², C = ((N+1)·m_p·h/2 +
/// N·m_t·h)·g, g the part of gravity along the plane's "up", (n × x)·ŷ·9.81),
/// solved far tighter by dopri5, at the trajectory's times.
template <class S, class Tr>
double worst_from_equation(const models::window_row_params& p, const Tr& tr, const std::vector<double>& times,
                           double th0, double* lowest) {
  const double h = p.height, g = -p.g.y() * p.axis.cross(Vec3d(1, 0, 0)).y(), N = windows;
  const double J = (N + 1) * p.m_post * h * h / 3 + N * p.m_top * h * h;
  const double C = ((N + 1) * p.m_post * h / 2 + N * p.m_top * h) * g;
  std::array<double, 2> y{th0, 0};
  auto rhs = [&](const std::array<double, 2>& z, std::array<double, 2>& dz, double) {
    dz[0] = z[1];
    dz[1] = -C * std::cos(z[0]) / J;
  };
  auto stepper = boost::numeric::odeint::make_dense_output(
      1e-14, 1e-14, boost::numeric::odeint::runge_kutta_dopri5<std::array<double, 2>>());
  double worst = 0;
  *lowest = th0;
  std::size_t k = 0;
  boost::numeric::odeint::integrate_times(stepper, rhs, y, times.begin(), times.end(), 1e-3,
                                          [&](const std::array<double, 2>& z, double) {
                                            for (int i = 0; i <= windows; ++i) {
                                              const int q = S::q_offset("post_pivot" + std::to_string(i));
                                              worst = std::max(worst, std::abs(tr.x[k][q] - z[0]));
                                            }
                                            *lowest = std::min(*lowest, tr.x[k][S::q_offset("post_pivot0")]);
                                            ++k;
                                          });
  REQUIRE(k == times.size());
  return worst;
}

}  // namespace

TEST_CASE("a row of 8 windows swings through its flat positions as its one-coordinate equation") {
  const models::window_row_params p;
  const auto s = models::window_row<windows>(p);
  using S = decltype(s);
  STATIC_REQUIRE(S::n_v == 2 * windows + 1);
  // Released at 0.3 rad above flat: it falls through θ = 0 at once and
  // reaches −π − 0.3, through the other flat position θ = −π.
  const double th0 = 0.3;
  const auto x = at_angle(s, th0);
  const auto times = output_times(0.0, 3.0, 0.05);
  const auto tr = simulate(s, x, times, {.tolerance = 1e-12});
  double lowest = 0;
  const double worst = worst_from_equation<S>(p, tr, times, th0, &lowest);
  INFO("worst post angle from the equation " << worst << " rad");
  CHECK(lowest < -std::numbers::pi - 0.2);  // both flat positions passed
  // Measured 2.4e-10: the damped steps through the flat positions (without
  // the damping the solve divides by the vanishing rows and the run is lost).
  CHECK(worst < 1e-9);
  const auto left = loop_residual(s, tr.x.back());
  CHECK(left.max_phi() < 1e-10);
}

TEST_CASE("a row of 8 windows with run-time axes: 24 of 40 rows repeat others and are left out") {
  // The plane tilted (axis (0, 0.6, 0.8)): the rows that repeat others are
  // combinations of rows that do not vanish, not rows of zeros.
  models::window_row_params p;
  p.axis = Vec3d(0, 0.6, 0.8);
  const auto s = models::window_row<windows, models::window_row_params, axis::any>(p);
  using S = decltype(s);
  STATIC_REQUIRE(S::n_v == 2 * windows + 1);
  STATIC_REQUIRE(constraint_count<S> == 5 * windows);
  // Hanging 0.6 rad off the bottom: a swing away from the flat positions.
  const double th0 = -std::numbers::pi / 2 + 0.6;
  const auto x = at_angle(s, th0);
  const auto r = loop_rank(s, x);
  CHECK(r.rank == 2 * windows);
  CHECK(r.dof == 1);
  const auto times = output_times(0.0, 3.0, 0.05);
  const auto tr = simulate(s, x, times, {.tolerance = 1e-12});
  double lowest = 0;
  const double worst = worst_from_equation<S>(p, tr, times, th0, &lowest);
  INFO("worst post angle from the equation " << worst << " rad");
  CHECK(lowest < -std::numbers::pi / 2 - 0.5);  // it swung through the bottom
  CHECK(worst < 1e-9);  // measured 2.8e-12, the integration's error at 1e-12
}
