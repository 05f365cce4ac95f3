// A double inverted pendulum on a cart, balanced by LQR: the upright
// equilibrium found by flange::equilibrium, the motion linearised there by
// flange::linearize (A exact, B for the cart's force), a discrete LQR gain
// from the Riccati iteration on (A, B) held over 10 ms samples, and the
// closed loop catching the pendulum from 10° off (docs/control.md).
//
//   lqr_balance                 simulate, write lqr_balance.csv, print a summary
//   lqr_balance --csv FILE      write the trajectory to FILE
//
// x = (s, φ1, φ2; ṡ, φ̇1, φ̇2): the cart's position, the lower link's angle
// from upright, the upper link's angle relative to the lower one.
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numbers>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <flange/flange.hpp>
#include <flange/simulate/equilibrium.hpp>
#include <flange/simulate/linearize.hpp>

using namespace flange;

namespace {
/// A uniform rod of length L and mass m, upright (along y) at φ = 0.
template <fixed_string Name>
auto rod(double L, double m) {
  Mat3d I = Mat3d::Zero();
  I(0, 0) = I(2, 2) = m * L * L / 12;
  I(1, 1) = 1e-4 * I(0, 0);
  return BodyShape<Name>({.r = Vec3d(0, L, 0), .r_cm = Vec3d(0, L / 2, 0), .m = m, .I = I});
}
}  // namespace

int main(int argc, char** argv) {
  const char* csv = "lqr_balance.csv";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else {
      std::cerr << "usage: lqr_balance [--csv FILE]\n";
      return 2;
    }
  }
  // The cart's force, held over each sample by the controller below.
  double u = 0;
  const auto pendulum =
      scene(World<"world">({.g = {0, -9.81, 0}}), prismatic<"cart", axis::x>([&u](auto, const auto&) { return u; }),
            PointMass<"cart_mass">({.m = 1.0}), Revolute<"hip", axis::z>{}, rod<"lower">(0.6, 0.4),
            Revolute<"elbow", axis::z>{}, rod<"upper">(0.5, 0.3),  //
            connect<"world.frame_b", "cart.frame_a">, connect<"cart.frame_b", "cart_mass.frame_a">,
            connect<"cart.frame_b", "hip.frame_a">, connect<"hip.frame_b", "lower.frame_a">,
            connect<"lower.frame_b", "elbow.frame_a">, connect<"elbow.frame_b", "upper.frame_a">);
  using S = decltype(pendulum);
  constexpr int n = S::n_state;

  // The upright equilibrium, from a guess off it (Newton lands on the nearest).
  const S::state_type x_star = equilibrium(pendulum, 0.0, S::state_type{0.0, 0.05, -0.05, 0, 0, 0});
  const auto lin = linearize<"cart">(pendulum, 0.0, x_star);
  Eigen::EigenSolver<Eigen::Matrix<double, n, n>> open(lin.A);
  double unstable = 0;
  for (int i = 0; i < n; ++i) unstable = std::max(unstable, open.eigenvalues()[i].real());

  // Zero-order hold over h: exp([A B; 0 0]·h) = [A_d B_d; 0 1].
  const double h = 0.01;
  Eigen::Matrix<double, n + 1, n + 1> aug = Eigen::Matrix<double, n + 1, n + 1>::Zero();
  aug.topLeftCorner<n, n>() = lin.A * h;
  aug.topRightCorner<n, 1>() = lin.B * h;
  const Eigen::Matrix<double, n + 1, n + 1> E = aug.exp();
  const Eigen::Matrix<double, n, n> Ad = E.topLeftCorner<n, n>();
  const Eigen::Matrix<double, n, 1> Bd = E.topRightCorner<n, 1>();

  // The discrete Riccati equation by iteration, to a fixed point.
  Eigen::Matrix<double, n, n> Q = Eigen::Matrix<double, n, n>::Zero();
  Q.diagonal() << 20, 100, 100, 2, 2, 2;
  const double R = 0.05;
  Eigen::Matrix<double, n, n> P = Q;
  int iterations = 0;
  for (double change = 1; change > 1e-12 && iterations < 200000; ++iterations) {
    const double s = R + (Bd.transpose() * P * Bd)(0, 0);
    const Eigen::Matrix<double, n, n> next =
        Q + Ad.transpose() * P * Ad - (Ad.transpose() * P * Bd) * (Bd.transpose() * P * Ad) / s;
    change = (next - P).cwiseAbs().maxCoeff() / next.cwiseAbs().maxCoeff();
    P = next;
  }
  const Eigen::Matrix<double, 1, n> K = (Bd.transpose() * P * Ad) / (R + (Bd.transpose() * P * Bd)(0, 0));
  Eigen::EigenSolver<Eigen::Matrix<double, n, n>> closed(Ad - Bd * K);
  double radius = 0;
  for (int i = 0; i < n; ++i) radius = std::max(radius, std::abs(closed.eigenvalues()[i]));

  // The closed loop from 10° off: u sampled every h, held between samples,
  // the motion integrated in full (not linearised) between them.
  S::state_type x = x_star;
  x[1] += 10 * std::numbers::pi / 180;
  std::ofstream out(csv);
  out << "t,s,phi1,phi2,u\n" << std::setprecision(10);
  auto stepper = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<S::state_type>());
  const double t_end = 8.0;
  double max_u = 0, max_tilt = 0;
  for (int k = 0; k * h < t_end - h / 2; ++k) {
    const double t = k * h;
    Eigen::Matrix<double, n, 1> dx;
    for (int i = 0; i < n; ++i) dx[i] = x[i] - x_star[i];
    u = -(K * dx)(0, 0);
    max_u = std::max(max_u, std::abs(u));
    max_tilt = std::max({max_tilt, std::abs(x[1]), std::abs(x[1] + x[2])});
    out << t << ',' << x[0] << ',' << x[1] << ',' << x[2] << ',' << u << '\n';
    odeint::integrate_adaptive(stepper, checked(pendulum, budget{}), x, t, t + h, h);
  }
  const double off = std::max({std::abs(x[0] - x_star[0]), std::abs(x[1] - x_star[1]), std::abs(x[2] - x_star[2])});

  std::cout << std::setprecision(4);
  std::cout << "flange LQR balance: a double inverted pendulum on a cart, state (s, φ1, φ2; ṡ, φ̇1, φ̇2)\n";
  std::cout << "  upright equilibrium: φ1 = " << x_star[1] << ", φ2 = " << x_star[2] << " (s = " << x_star[0]
            << "); open loop's fastest growth " << unstable << " 1/s\n";
  std::cout << "  LQR gain K = [" << K << "] (Riccati: " << iterations << " iterations, h = " << h
            << " s); closed loop's spectral radius " << radius << "\n";
  std::cout << "  caught from 10° off: largest tilt " << max_tilt * 180 / std::numbers::pi << "°, largest force "
            << max_u << " N; after " << t_end << " s the state is " << std::scientific << off
            << " from upright\n";
  std::cout << "  wrote " << csv << "\n";
  return radius < 1 && off < 1e-4 ? 0 : 1;
}
