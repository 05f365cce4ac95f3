// linearize and equilibrium: the cart-pole's A and B against their closed
// form, a driven four-bar's B against the difference of two forces (v̇ is
// affine in them) and its closed loop's Jacobian against A − B·K, and the
// equilibria Newton finds against the closed forms and the four-bar's
// hand-written equation of motion.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include <flange/components/body.hpp>
#include <flange/components/fixed_translation.hpp>
#include <flange/components/world.hpp>
#include <flange/joints/prismatic.hpp>
#include <flange/joints/revolute.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/equilibrium.hpp>
#include <flange/simulate/linearize.hpp>

using namespace flange;

namespace {
constexpr double g = 9.81, M = 1.3, m = 0.4, l = 0.7;

/// A cart on a rail (x along it) carrying a pole: a point mass m at l from
/// the pivot, φ = 0 upright, the cart pushed by f.
template <class F>
auto cart_pole(F f) {
  return scene(World<"world">({.g = {0, -g, 0}}), prismatic<"cart", axis::x>(f), PointMass<"cart_mass">({.m = M}),
               Revolute<"pivot", axis::z>{}, FixedTranslation<"pole">({.d = {0, l, 0}}), PointMass<"bob">({.m = m}),
               connect<"world.frame_b", "cart.frame_a">, connect<"cart.frame_b", "cart_mass.frame_a">,
               connect<"cart.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "pole.frame_a">,
               connect<"pole.frame_b", "bob.frame_a">);
}

/// The four-bar of models::fourbar with its crank driven by tau(t, x).
template <class Tau>
auto driven_fourbar(const models::fourbar_params& p, Tau tau) {
  return scene(World<"world">({.g = p.g}), revolute<"crank_pivot", axis::z>(tau),
               models::bar<"crank">(p.crank, p.m_crank), Revolute<"crank_pin", axis::z>{},
               models::bar<"coupler">(p.coupler, p.m_coupler), Revolute<"rocker_pin", axis::z>{},
               models::bar<"rocker">(p.rocker, p.m_rocker), FixedTranslation<"ground">({.d = Vec3d(p.ground, 0, 0)}),
               Revolute<"rocker_pivot", axis::z>{}, connect<"world.frame_b", "crank_pivot.frame_a">,
               connect<"crank_pivot.frame_b", "crank.frame_a">, connect<"crank.frame_b", "crank_pin.frame_a">,
               connect<"crank_pin.frame_b", "coupler.frame_a">, connect<"coupler.frame_b", "rocker_pin.frame_a">,
               connect<"rocker_pin.frame_b", "rocker.frame_a">, connect<"world.frame_b", "ground.frame_a">,
               connect<"ground.frame_b", "rocker_pivot.frame_a">, connect<"rocker.frame_b", "rocker_pivot.frame_b">);
}

/// The four-bar closed at crank angle θ2 with crank rate w2.
template <class S>
typename S::state_type fourbar_state(const models::fourbar_params& p, double th2, double w2) {
  const auto q = models::fourbar_coordinates(p, th2, models::freudenstein_rocker(p, th2));
  typename S::state_type x{q[0], q[1], q[2], w2, 0, 0};
  return x;
}
}  // namespace

TEST_CASE("the cart-pole's linearisation at upright equals its closed form") {
  // Lagrange in (s, φ), tip at (s − l·sin φ, l·cos φ): mass matrix
  // [M + m, −m·l; −m·l, m·l²] at φ = 0, gravity's force (0, m·g·l·φ).
  const auto cp = cart_pole(0.0);
  const auto lin = linearize<"cart", "pivot">(cp, 0.0, decltype(cp)::state_type{0.25, 0, 0, 0});
  Eigen::Matrix4d A;
  A << 0, 0, 1, 0,  //
      0, 0, 0, 1,   //
      0, m * g / M, 0, 0, 0, g * (M + m) / (M * l), 0, 0;
  Eigen::Matrix<double, 4, 2> B;
  B << 0, 0, 0, 0, 1 / M, 1 / (M * l), 1 / (M * l), (M + m) / (M * m * l * l);
  CHECK((lin.A - A).cwiseAbs().maxCoeff() <= 1e-14 * A.cwiseAbs().maxCoeff());
  CHECK((lin.B - B).cwiseAbs().maxCoeff() <= 1e-14 * B.cwiseAbs().maxCoeff());
  CHECK(lin.inputs[0] == "cart");
  CHECK(lin.inputs[1] == "pivot");
  // One input: B's column for the cart alone.
  const auto cart_only = linearize<"cart">(cp, 0.0, decltype(cp)::state_type{0.25, 0, 0, 0});
  CHECK(cart_only.B == lin.B.col(0));
}

TEST_CASE("a driven four-bar's B is the difference the drive's force makes, and its closed loop's Jacobian is A − B·K") {
  const models::fourbar_params p;
  // τ = τ0 − K·(x − x*): the feedback vanishes at the state linearised about.
  double tau0 = 0, k_crank = 0, k_rate = 0, th2_star = 0, w2_star = 0;
  auto drive = [&](auto, const auto& x) {
    return tau0 - k_crank * (x.q(0) - th2_star) - k_rate * (x.v(0) - w2_star);
  };
  const auto fb = driven_fourbar(p, drive);
  using S = decltype(fb);
  for (double th2 : {0.3, 1.2, 2.5, 4.0}) {
    const auto x = fourbar_state<S>(p, th2, 1.7);
    th2_star = th2, w2_star = 1.7;
    const auto lin = linearize<"crank_pivot", "crank_pin">(fb, 0.0, x);
    // v̇ is affine in the crank's torque: the difference of two torques a
    // unit apart, centred, gives the column up to the rounding of v̇.
    S::state_type fp, fm;
    tau0 = 0.5;
    fb(x, fp, 0.0);
    tau0 = -0.5;
    fb(x, fm, 0.0);
    tau0 = 0;
    double scale = 1;
    for (int i = 0; i < S::n_state; ++i) scale = std::max(scale, std::abs(fp[i]));
    for (int i = 0; i < S::n_state; ++i) CHECK(std::abs(lin.B(i, 0) - (fp[i] - fm[i])) <= 1e-13 * scale);
    // The loop turns a torque at the crank pin into the same motion as at
    // the pivot, less what the crank's own inertia takes: the columns differ.
    CHECK((lin.B.col(0) - lin.B.col(1)).norm() > 0.1 * lin.B.col(0).norm());
    // The loop's constraint holds for each column: G·w = 0.
    const auto k = detail::loop_kinematics<S>(fb, x.data(), x.data() + S::n_q);
    for (int c = 0; c < 2; ++c)
      CHECK((k.G * lin.B.col(c).tail<3>()).cwiseAbs().maxCoeff() <= 1e-14 * k.G.cwiseAbs().maxCoeff() *
                                                                          lin.B.col(c).cwiseAbs().maxCoeff());
    // With feedback τ = −K·(x − x*) through the drive, the dual numbers see
    // it in the Jacobian: A − B·K.
    k_crank = 3.0, k_rate = 0.4;
    Eigen::Matrix<double, 1, S::n_state> K = Eigen::Matrix<double, 1, S::n_state>::Zero();
    K(0, 0) = k_crank;
    K(0, 3) = k_rate;
    const auto closed = jacobian(fb, 0.0, x);
    k_crank = k_rate = 0;
    const Eigen::Matrix<double, S::n_state, S::n_state> expected = lin.A - lin.B.col(0) * K;
    CHECK((closed - expected).cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, expected.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("equilibrium finds the cart-pole upright and the four-bar hanging, at rest") {
  SECTION("the cart-pole: φ = 0 or π with the cart anywhere; Newton goes to the nearest") {
    const auto cp = cart_pole(0.0);
    const auto x = equilibrium(cp, 0.0, decltype(cp)::state_type{0.3, 0.2, 0.1, -0.3});
    CHECK(std::abs(x[1]) <= 1e-11);
    CHECK(std::abs(x[2]) <= 1e-11);
    CHECK(std::abs(x[3]) <= 1e-11);
    CHECK(std::abs(x[0] - 0.3) < 0.5);
    const auto down = equilibrium(cp, 0.0, decltype(cp)::state_type{0, 2.9, 0, 0});
    CHECK(std::abs(down[1] - std::numbers::pi) <= 1e-11);
  }
  SECTION("the four-bar under gravity: the hand-written equation of motion's θ̈2 vanishes there") {
    const models::fourbar_params p;
    const auto fb = driven_fourbar(p, 0.0);
    using S = decltype(fb);
    for (double guess : {-1.2, 1.8}) {
      const auto x = equilibrium(fb, 0.0, fourbar_state<S>(p, guess, 0.5), {.tolerance = 1e-12});
      CHECK(std::abs(models::fourbar_crank_acceleration(p, x[0], 0)) <= 1e-10);
      for (int i = 3; i < 6; ++i) CHECK(std::abs(x[i]) <= 1e-12);
      // On the loop: the rocker where Freudenstein's equation puts it.
      const auto q = models::fourbar_coordinates(p, x[0], models::freudenstein_rocker(p, x[0]));
      CHECK(std::abs(x[1] - q[1]) <= 1e-9);
      CHECK(std::abs(x[2] - q[2]) <= 1e-9);
    }
  }
}

TEST_CASE("equilibrium says why it found none, naming the entry of ẋ and its joint") {
  const auto pushed = cart_pole(2.0);  // a constant force nothing balances
  try {
    (void)equilibrium(pushed, 0.0, decltype(pushed)::state_type{0, 0, 0, 0});
    FAIL("no error");
  } catch (const error& e) {
    const std::string what = e.what();
    CHECK(what.find("no state with ẋ = 0 found") != std::string::npos);
    CHECK(what.find("joint \"cart\"") != std::string::npos);
    CHECK(what.find("no longer decrease") != std::string::npos);
  }
  const auto cp = cart_pole(0.0);
  CHECK_THROWS_AS(equilibrium(cp, 0.0, decltype(cp)::state_type{}, {.tolerance = 0}), parameter_error);
}
