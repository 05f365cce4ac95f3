// Revolute drives (Modelica's useAxisFlange with a torque source, in one
// component): a torque input τ on the joint's axis, a constant or a callable
// of t or (t, x), against the paper's closed form, against the same arm
// driven by a separate Torque element, with an axis law, connected either
// way round, through the residual and the listing, and through the
// dual-number Jacobian.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <sstream>

#include <flange/flange.hpp>
#include <flange/models/paper.hpp>
#include <flange/simulate/jacobian.hpp>

using namespace flange;

namespace {

/// The paper's arm with the motor as the joint's own drive.
template <class Tau>
auto driven_arm(const models::robot_arm_params& p, Tau tau) {
  return scene(World<"world">({.g = {0, -p.g, 0}}), revolute<"joint", axis::z>(std::move(tau)),
               FixedTranslation<"rod">({.d = {p.d, 0, 0}}),
               Body<"mass">({.m = p.m, .J = Vec3d(p.Jx, p.Jz, p.Jz).asDiagonal()}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">);
}

}  // namespace

TEST_CASE("a constant drive torque gives the paper's closed form, as a Torque element does") {
  const models::robot_arm_params p;
  const auto arm = driven_arm(p, 1.5);
  const auto with_torque = models::robot_arm(p, Vec3d(0, 0, 1.5));
  using Arm = decltype(arm);
  static_assert(Arm::n_equations == Arm::n_unknowns);
  for (double phi : {-2.0, -0.3, 0.0, 0.7, 2.9})
    for (double w : {-3.0, 0.0, 1.2}) {
      Arm::state_type x{phi, w}, dx, dy;
      arm(x, dx, 0.0);
      with_torque(x, dy, 0.0);
      const double closed = models::robot_arm_theta_dd(p, 1.5, phi + std::numbers::pi / 2);
      CHECK(dx[0] == w);
      CHECK(std::abs(dx[1] - closed) <= 1e-13 * (1 + std::abs(closed)));
      CHECK(std::abs(dx[1] - dy[1]) <= 1e-13 * (1 + std::abs(closed)));
    }
}

TEST_CASE("a PD drive τ(t, x) swings the arm up like the same controller in a Torque element") {
  const models::robot_arm_params p;
  const double target = 0.75 * std::numbers::pi - std::numbers::pi / 2;  // 135° from the downward vertical
  auto pd = [target](auto, const auto& x) { return 30.0 * (target - x.q(0)) - 5.0 * x.v(0); };
  auto pd_vec = [pd](auto t, const auto& x) {
    using T = decltype(x.q(0));
    return Eigen::Matrix<T, 3, 1>(T(0), T(0), pd(t, x));
  };
  const auto arm = driven_arm(p, pd);
  const auto with_torque = models::robot_arm(p, pd_vec);
  using X = decltype(arm)::state_type;
  X x{-std::numbers::pi / 2, 0.0}, y = x;
  auto stepper = [] { return odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<X>()); };
  odeint::integrate_adaptive(stepper(), arm, x, 0.0, 3.0, 1e-3);
  odeint::integrate_adaptive(stepper(), with_torque, y, 0.0, 3.0, 1e-3);
  INFO("drive: φ = " << x[0] << ", Torque element: φ = " << y[0]);
  CHECK(std::abs(x[0] - y[0]) < 1e-9);
  CHECK(std::abs(x[1] - y[1]) < 1e-9);
  // The controller has a steady-state error m·g·d·sin θ / kp: it settles there.
  const double theta = x[0] + std::numbers::pi / 2;
  CHECK(std::abs(30.0 * (target - x[0]) - p.m * p.g * p.d * std::sin(theta)) < 1e-3);

  SECTION("the residual vanishes along the driven trajectory, and the listing shows τ") {
    X z{-std::numbers::pi / 2, 0.0};
    double worst = 0;
    odeint::integrate_const(odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>()), arm, z, 0.0,
                            2.0, 0.05, record(arm, [&](const auto& sol) {
                              worst = std::max(worst, scaled_residual(arm, sol));
                            }));
    INFO("largest scaled residual " << worst);
    CHECK(worst < 1e-12);
    std::ostringstream os;
    print_equations(arm, os);
    CHECK(os.str().find("τ = −M3·n") != std::string::npos);  // frame 3 is joint.frame_b
  }
  SECTION("the exact Jacobian sees the drive's dependence on (φ, φ̇)") {
    const X z{0.3, -0.4};
    const auto J = jacobian(arm, 0.0, z);
    const auto J_torque = jacobian(with_torque, 0.0, z);
    CHECK((J - J_torque).cwiseAbs().maxCoeff() < 1e-12);
    const double I = p.Jz + p.m * p.d * p.d;
    CHECK(std::abs(J(1, 1) - (-5.0 / I)) < 1e-12);  // ∂φ̈/∂φ̇ = −kd / I
  }
}

TEST_CASE("a drive with an axis law adds both, and connected backwards it still drives its coordinate") {
  const models::robot_arm_params p;
  auto arm_law = scene(World<"world">({.g = {0, -p.g, 0}}),
                       Revolute<"joint", axis::z, axis_law::spring_damper, double>(
                           {.tau = 0.8, .c = 4.0, .d = 0.3, .phi0 = 0.2}),
                       FixedTranslation<"rod">({.d = {p.d, 0, 0}}),
                       Body<"mass">({.m = p.m, .J = Vec3d(p.Jx, p.Jz, p.Jz).asDiagonal()}),
                       connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                       connect<"rod.frame_b", "mass.frame_a">);
  using X = decltype(arm_law)::state_type;
  const X x{0.5, -1.0};
  X dx;
  arm_law(x, dx, 0.0);
  const double I = p.Jz + p.m * p.d * p.d;
  const double expected =
      (0.8 - 4.0 * (0.5 - 0.2) - 0.3 * (-1.0) - p.m * p.g * p.d * std::sin(0.5 + std::numbers::pi / 2)) / I;
  CHECK(std::abs(dx[1] - expected) < 1e-13);

  // frame_b on the World, frame_a on the rod: φ is then the World's angle
  // relative to the rod, the rod turns by −φ, and τ > 0 drives φ up.
  auto reversed = scene(World<"world">({.g = {0, -p.g, 0}}), revolute<"joint", axis::z>(1.5),
                        FixedTranslation<"rod">({.d = {p.d, 0, 0}}),
                        Body<"mass">({.m = p.m, .J = Vec3d(p.Jx, p.Jz, p.Jz).asDiagonal()}),
                        connect<"world.frame_b", "joint.frame_b">, connect<"joint.frame_a", "rod.frame_a">,
                        connect<"rod.frame_b", "mass.frame_a">);
  const X y{-0.4, 0.0};
  X dy;
  reversed(y, dy, 0.0);
  // The rod's angle is −φ: I·(−φ̈) = −τ − m·g·d·cos(−φ), so φ̈ = (τ + m·g·d·cos φ) / I.
  CHECK(std::abs(dy[1] - (1.5 + p.m * p.g * p.d * std::cos(0.4)) / I) < 1e-13);
}

TEST_CASE("a drive's torque must be finite") {
  CHECK_THROWS_WITH((Revolute<"j", axis::z, axis_law::none, double>({.tau = std::nan("")})),
                    Catch::Contains("Revolute \"j\"") && Catch::Contains("tau"));
}
