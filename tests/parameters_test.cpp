// Bad parameters throw at construction, naming the component and the value;
// a singularity found during simulation throws with the time and the state.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <string_view>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/simulate/jacobian.hpp>

using namespace flange;
using Catch::Matchers::Contains;

namespace {
const double not_a_number = std::numeric_limits<double>::quiet_NaN();
}

TEST_CASE("a body refuses unphysical mass and inertia") {
  CHECK_THROWS_WITH(Body<"mass">({.m = -1.0}), Contains("Body \"mass\"") && Contains("-1") && Contains("negative"));
  CHECK_THROWS_WITH(Body<"mass">({.m = not_a_number}), Contains("Body \"mass\"") && Contains("not finite"));
  Mat3d J = Mat3d::Identity();
  J(0, 1) = 0.5;
  CHECK_THROWS_WITH(Body<"mass">({.m = 1.0, .J = J}), Contains("Body \"mass\"") && Contains("not symmetric"));
  CHECK_THROWS_WITH(Body<"arm">({.m = 1.0, .J = Vec3d(1, 1, -0.5).asDiagonal()}),
                    Contains("Body \"arm\"") && Contains("positive semi-definite") && Contains("-0.5"));
  CHECK_THROWS_WITH(Body<"disk">({.m = 1.0, .J = Vec3d(1, 1, 3).asDiagonal()}),
                    Contains("Body \"disk\"") && Contains("triangle inequality") && Contains("3"));
  CHECK_THROWS_WITH(Body<"mass">({.m = 1.0, .r_cm = {0.1, 0, 0}}), Contains("cm::offset"));
  CHECK_NOTHROW(Body<"mass", cm::offset>({.m = 1.0, .r_cm = {0.1, 0, 0}}));
  CHECK_NOTHROW(Body<"point">({.m = 1.0}));  // a point mass has J = 0
}

TEST_CASE("the inertia check decides by the principal moments to 1e-12 of the largest entry") {
  // Tensors R·diag(a, b, c)·R' of known principal moments, turned by random
  // rotations: accepted exactly when the moments are non-negative and obey
  // the triangle inequality, the boundary cases (a lamina, c = a + b; a rod,
  // one moment zero) included, whatever the turn.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto turn = [&] {
    const Vec3d axis(u(rng), u(rng), u(rng));
    return Eigen::AngleAxisd(3 * u(rng), axis.normalized()).toRotationMatrix().eval();
  };
  struct moments {
    double a, b, c;
    bool physical;
  };
  const moments cases[] = {{1, 2, 3, true},     {1, 1, 2, true},         {0.3, 0.7, 1.0, true},
                           {0, 1, 1, true},     {2, 2, 2, true},         {1, 2, 3 + 1e-9, false},
                           {1, 1, 2.001, false}, {-1e-6, 1, 1, false},   {0, 0, 0, true},
                           {5e-7, 1, 1, true},  {1e3, 1e3, 2e3, true},   {1e-3, 2e-3, 3.1e-3, false}};
  for (const auto& m : cases)
    for (int k = 0; k < 20; ++k) {
      const Mat3d R = turn();
      const Mat3d J = R * Vec3d(m.a, m.b, m.c).asDiagonal() * R.transpose();
      const Mat3d Js = (J + J.transpose()) / 2;  // symmetric to the bit, as a user's tensor is
      INFO("moments " << m.a << " " << m.b << " " << m.c << ", turn " << k);
      if (m.physical) {
        CHECK_NOTHROW(Body<"b">({.m = 1.0, .J = Js}));
      } else {
        CHECK_THROWS_AS(Body<"b">({.m = 1.0, .J = Js}), parameter_error);
      }
      // The moments the message gives: the closed form against the construction.
      const Vec3d lam = detail::symmetric_eigenvalues(Js);
      const double scale = std::max({std::abs(m.a), std::abs(m.b), std::abs(m.c), 1e-300});
      std::array<double, 3> want{m.a, m.b, m.c};
      std::sort(want.begin(), want.end());
      for (int i = 0; i < 3; ++i) CHECK(std::abs(lam(i) - want[i]) <= 1e-14 * scale);
    }
}

TEST_CASE("messages write numbers to 17 digits and vectors and matrices on one line") {
  CHECK(detail::concat("x = ", 0.1, ", n = ", 42, ", c = ", 'c') == "x = 0.10000000000000001, n = 42, c = c");
  CHECK(detail::concat(Vec3d(1, -2.5, 3).transpose()) == "1 -2.5 3");
  CHECK(detail::concat(Vec3d(1, -2.5, 3)) == "1 -2.5 3");
  Mat3d A;
  A << 1, 2, 3, 4, 5, 6, 7, 8, 9.5;
  CHECK(detail::concat("[", A, "]") == "[1 2 3; 4 5 6; 7 8 9.5]");
  CHECK(detail::concat(std::string("s"), std::string_view("v"), 1e300, -0.0) == "sv1.0000000000000001e+300-0");
  CHECK(detail::brief(1.0 / 3) == "0.333333");
  CHECK(detail::concat(std::numeric_limits<double>::infinity()) == "inf");
}

TEST_CASE("joints refuse a zero or non-finite axis") {
  CHECK_THROWS_WITH(Revolute<"elbow">({.n = {0, 0, 0}}), Contains("Revolute \"elbow\"") && Contains("is zero"));
  CHECK_THROWS_WITH(Revolute<"elbow">({.n = {not_a_number, 0, 1}}), Contains("Revolute \"elbow\"") && Contains("not finite"));
  CHECK_THROWS_WITH(Prismatic<"rail">({.n = {0, 0, 0}, .f = 0.0}), Contains("Prismatic \"rail\""));
  CHECK_THROWS_WITH(Prismatic<"rail">({.n = {1, 0, 0}, .f = not_a_number}), Contains("Prismatic \"rail\"") && Contains("f"));
  CHECK(Revolute<"elbow">({.n = {0, 0, 2}}).n() == Vec3d::UnitZ());  // normalised, as Modelica does
}

TEST_CASE("other components refuse non-finite parameters") {
  CHECK_THROWS_WITH(FixedTranslation<"rod">({.d = {not_a_number, 0, 0}}), Contains("FixedTranslation \"rod\""));
  CHECK_THROWS_WITH(World<"world">({.g = {0, not_a_number, 0}}), Contains("World \"world\"") && Contains("gravity"));
  CHECK_THROWS_WITH(Torque<"motor">({.M_ext = Vec3d(0, 0, not_a_number)}), Contains("Torque \"motor\""));
}

TEST_CASE("a massless end body gives a singular mass matrix, reported with time and state") {
  const auto arm = models::robot_arm({.m = 0.0, .d = 0.5, .Jx = 0.0, .Jz = 0.0});
  std::array<double, 2> x{0.25, -1.5}, dx;
  CHECK_THROWS_AS(arm(x, dx, 2.5), simulation_error);
  CHECK_THROWS_WITH(arm(x, dx, 2.5), Contains("singular mass matrix") && Contains("t = 2.5") &&
                                         Contains("q = [0.25]") && Contains("-1.5") && Contains("joint \"joint\""));
}

TEST_CASE("a massless link in the middle of a chain names its joint") {
  // A 2-link chain whose first link carries nothing: its joint still moves the
  // second link, so M is regular; with the second link massless too, the
  // second joint moves nothing and is named.
  models::chain_params<2> p;
  for (int i = 0; i < 2; ++i) {
    p.axis[i] = Vec3d::UnitZ();
    p.d[i] = Vec3d(0.5, 0, 0);
    p.m[i] = 0.0;
    p.J[i] = Mat3d::Zero();
  }
  p.m[0] = 1.0;
  const auto chain = models::chain<2, models::planar_axes>(p);
  std::array<double, 4> x{0.1, 0.2, 0.0, 0.0}, dx;
  CHECK_THROWS_WITH(chain(x, dx, 0.0), Contains("joint \"j1\" (v[1])"));
}

TEST_CASE("a branch that moves nothing names its joint") {
  // A branched tree: "hip" carries two legs; the right leg's knee turns a
  // point mass on its own axis, so it moves nothing. The other entries of
  // the mass matrix (between the legs) are zero, not junk.
  auto make = [](double m) {
    return scene(World<"world">{}, Revolute<"hip", axis::z>{}, Body<"pelvis">({.m = 2.0, .J = Mat3d::Identity()}),
                 FixedTranslation<"left">({.d = {0.3, 0, 0}}), FixedTranslation<"right">({.d = {-0.3, 0, 0}}),
                 Revolute<"knee_l", axis::z>{}, Revolute<"knee_r", axis::z>{},
                 FixedTranslation<"shin">({.d = {0, -0.5, 0}}), Body<"foot_l">({.m = 1.0}),
                 PointMass<"foot_r">({.m = m}), connect<"world.frame_b", "hip.frame_a">,
                 connect<"hip.frame_b", "pelvis.frame_a">, connect<"hip.frame_b", "left.frame_a">,
                 connect<"hip.frame_b", "right.frame_a">, connect<"left.frame_b", "knee_l.frame_a">,
                 connect<"right.frame_b", "knee_r.frame_a">, connect<"knee_l.frame_b", "shin.frame_a">,
                 connect<"shin.frame_b", "foot_l.frame_a">, connect<"knee_r.frame_b", "foot_r.frame_a">);
  };
  std::array<double, 6> x{0.1, 0.2, 0.3, 0.0, 0.0, 0.0}, dx;
  CHECK_THROWS_WITH(make(1.0)(x, dx, 0.0), Contains("joint \"knee_r\" (v[2])") && Contains("singular mass matrix"));
}

TEST_CASE("a point mass on a skew joint axis through it is a singular mass matrix, named with its cause") {
  // The axis passes through the mass: turning the joint moves nothing. Its
  // diagonal is round-off (~1e-17 of m·|d|²), which an absolute test takes for
  // a mass: the relative test reports it.
  const Vec3d n = Vec3d(1, 2, 3).normalized();
  auto make = [&](const Vec3d& d) {
    return scene(World<"world">{}, Revolute<"joint">({.n = n}), FixedTranslation<"rod">({.d = d}),
                 PointMass<"mass">({.m = 1.0}), connect<"world.frame_b", "joint.frame_a">,
                 connect<"joint.frame_b", "rod.frame_a">, connect<"rod.frame_b", "mass.frame_a">);
  };
  const auto skew = make(0.7 * n);
  std::array<double, 2> x{0.5, 0.0}, dx;
  CHECK_THROWS_WITH(skew(x, dx, 0.0), Contains("singular mass matrix") && Contains("joint \"joint\"") &&
                                          Contains("passes through all the mass it moves") && Contains("t = 0"));
  // 1e-4 m off the axis the joint is regular (its pivot is 1e-8 of the scale,
  // far above the tolerance), and q̈ = M / (m·r²) holds to round-off amplified
  // by that ratio.
  const Vec3d off = n.cross(Vec3d::UnitX()).normalized() * 1e-4;
  const auto near = scene(World<"world", gravity_kind::none>{}, Revolute<"joint">({.n = n}),
                          Torque<"motor">({.M_ext = 3e-8 * n}), FixedTranslation<"rod">({.d = 0.7 * n + off}),
                          PointMass<"mass">({.m = 1.0}), connect<"world.frame_b", "joint.frame_a">,
                          connect<"world.frame_b", "motor.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                          connect<"joint.frame_b", "motor.frame_b">, connect<"rod.frame_b", "mass.frame_a">);
  near(x, dx, 0.0);
  CHECK(dx[1] == Approx(3e-8 / 1e-8).epsilon(1e-6));
}

TEST_CASE("axes of any finite length are normalised without overflow or underflow") {
  CHECK((Revolute<"a">({.n = {0, 0, 1e300}}).n() - Vec3d::UnitZ()).norm() == 0);
  CHECK((Revolute<"a">({.n = {1e-200, 0, 0}}).n() - Vec3d::UnitX()).norm() == 0);
  CHECK((Prismatic<"p">({.n = {3e-300, 4e-300, 0}}).n() - Vec3d(0.6, 0.8, 0)).norm() < 1e-16);
  CHECK((Revolute<"a">({.n = {1e308, 1e308, 1e308}}).n() - Vec3d::Ones().normalized()).norm() < 1e-16);
  CHECK_THROWS_WITH(Revolute<"elbow">({.n = {0, 0, 0}}), Contains("Revolute \"elbow\"") && Contains("is zero"));
}

TEST_CASE("lengths and masses that overflow the dynamics are refused with their cause") {
  CHECK_THROWS_WITH(models::robot_arm({.m = 1.0, .d = 1e160}),
                    Contains("FixedTranslation \"rod\"") && Contains("overflows") && Contains("1e+160"));
  CHECK_THROWS_WITH(models::robot_arm({.m = 1e300, .d = 1e10}), Contains("overflows"));
  // Large but representable: accepted, and the arm's closed form holds.
  const models::robot_arm_params big{.m = 1.0, .d = 1e100, .Jx = 0.01, .Jz = 0.02};
  const auto arm = models::robot_arm(big);
  std::array<double, 2> x{0.3, 0.0}, dx;
  arm(x, dx, 0.0);
  CHECK(dx[1] == Approx(models::robot_arm_theta_dd(big, 0.0, 0.3 + 1.5707963267948966)).epsilon(1e-12));
}

TEST_CASE("a state of the wrong size is refused with both sizes, directly and through Odeint") {
  const auto arm = models::robot_arm();
  std::vector<double> x(1, 0.1), dx(1);
  CHECK_THROWS_WITH(arm(x, dx, 0.0), Contains("size 1") && Contains("2 entries"));
  CHECK_THROWS_WITH(odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<std::vector<double>>()),
                                               arm, x, 0.0, 1.0, 1e-3),
                    Contains("size 1"));
  CHECK_THROWS_WITH(recover(arm, 0.0, std::vector<double>(3, 0.0)), Contains("size 3"));
  CHECK_THROWS_WITH(jacobian(arm, 0.0, Eigen::VectorXd::Zero(5)), Contains("size 5"));
  // The right size works with a std::vector, Odeint's most common state.
  std::vector<double> y{0.1, 0.0};
  odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<std::vector<double>>()),
                             arm, y, 0.0, 0.1, 1e-3);
  CHECK(y.size() == 2);
}

TEST_CASE("the 3-D joints refuse bad axes, orientations and quaternions, naming the joint and the value") {
  CHECK_THROWS_WITH(Universal<"cardan">({.n_a = {1, 0, 0}, .n_b = {2, 0, 0}}),
                    Contains("Universal \"cardan\"") && Contains("parallel"));
  CHECK_THROWS_WITH(Universal<"cardan">({.n_a = {0, 0, 0}, .n_b = {0, 1, 0}}),
                    Contains("Universal \"cardan\"") && Contains("is zero"));
  CHECK_THROWS_WITH(Planar<"table">({.n = {0, 0, 1}, .n_x = {0, 0, 3}}), Contains("Planar \"table\"") && Contains("parallel"));
  CHECK_THROWS_WITH(Cylindrical<"piston">({.n = {0, 0, 0}}), Contains("Cylindrical \"piston\"") && Contains("is zero"));
  Mat3d skewed = Mat3d::Identity();
  skewed(0, 1) = 0.1;
  CHECK_THROWS_WITH(FixedRotation<"turn">({.R = orientation::matrix(skewed)}),
                    Contains("FixedRotation \"turn\"") && Contains("is not a rotation"));
  CHECK_THROWS_WITH(FixedRotation<"turn">({.R = orientation::matrix(-Mat3d::Identity())}),
                    Contains("FixedRotation \"turn\"") && Contains("det R = -1"));
  const auto top = scene(World<"world">{}, Spherical<"ball">{}, Body<"b">({.m = 1.0, .J = Mat3d::Identity()}),
                         connect<"world.frame_b", "ball.frame_a">, connect<"ball.frame_b", "b.frame_a">);
  auto x = neutral_state(top);
  CHECK_THROWS_WITH(set_joint<"ball">(top, x, {.R = orientation::matrix(skewed)}),
                    Contains("Spherical \"ball\"") && Contains("initial orientation") && Contains("not a rotation"));
  // A quaternion written by hand with the wrong norm: the checked system names
  // the joint, the value and the fix.
  x = {0.5, 0.5, 0.5, 0.9, 0, 0, 0};
  budget b;
  decltype(top)::state_type dx;
  CHECK_THROWS_WITH(checked(top, b)(x, dx, 0.0), Contains("Spherical \"ball\"") && Contains("squared norm 1.56") &&
                                                   Contains("normalize") && Contains("t = 0"));
  normalize(top, x);
  CHECK_NOTHROW(checked(top, b)(x, dx, 0.0));
}

TEST_CASE("a state set by hand is checked, through the joints' own state or the plain default") {
  // Revolute, Universal and FreeMotion: the plain default {.q, .v} (one
  // coordinate), {.q = {…}, .v = {…}} (two), and a joint's own state type.
  const auto s = scene(World<"world">{}, Revolute<"hinge", axis::z>{}, Body<"a">({.m = 1.0}),
                       Universal<"cardan">({.n_a = {1, 0, 0}, .n_b = {0, 1, 0}}), Body<"b">({.m = 1.0}),
                       FreeMotion<"free">{}, Body<"c">({.m = 1.0, .J = Mat3d::Identity()}),
                       connect<"world.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "a.frame_a">,
                       connect<"a.frame_a", "cardan.frame_a">, connect<"cardan.frame_b", "b.frame_a">,
                       connect<"world.frame_b", "free.frame_a">, connect<"free.frame_b", "c.frame_a">);
  static_assert(plain_joint<Revolute<"hinge", axis::z>>() && plain_joint<Universal<"u">>());
  static_assert(!plain_joint<FreeMotion<"free">>() && !plain_joint<Spherical<"s">>());
  const auto x = initial_state<"hinge", "cardan", "free">(s, {.q = 0.3, .v = -1}, {.q = {0.1, 0.2}, .v = {3, 4}},
                                                       {.r = {1, 2, 3}, .v = {}, .R = {}, .w = {}});
  CHECK(x[0] == 0.3);
  CHECK((x[1] == 0.1 && x[2] == 0.2));
  CHECK((x[3] == 1 && x[4] == 2 && x[5] == 3 && x[9] == 1));  // FreeMotion: r, then the unit quaternion
  CHECK(x[10] == -1);
  CHECK((x[11] == 3 && x[12] == 4));
  CHECK_THROWS_WITH(initial_state<"hinge">(s, {.q = not_a_number}),
                    Contains("Revolute \"hinge\"") && Contains("initial coordinate") && Contains("nan"));
  CHECK_THROWS_WITH(initial_state<"cardan">(s, {.v = {0, not_a_number}}),
                    Contains("Universal \"cardan\"") && Contains("initial rate 1"));
  // A FreeMotion's quaternion (q[3..6]) off unit norm: the same check as a Spherical's.
  auto y = x;
  y[9] = 1.25;
  budget b;
  decltype(s)::state_type dy;
  CHECK_THROWS_WITH(checked(s, b)(y, dy, 0.0), Contains("FreeMotion \"free\"") && Contains("squared norm 1.5625"));
  normalize(s, y);
  CHECK(y[9] == 1.0);
}

TEST_CASE("a diverged (NaN) state is reported as such, not as a singular mass matrix") {
  // The crane's mass matrix depends on the rope angle: a NaN angle makes
  // every pivot NaN, and the message names the state, not a joint.
  const auto crane = models::gantry_crane();
  std::array<double, 4> x{0.0, not_a_number, 0.0, 1.0}, dx;
  CHECK_THROWS_WITH(crane(x, dx, 4.95), Contains("the state is not finite at t = 4.95") && Contains("diverged") &&
                                            !Contains("singular mass matrix"));
}

TEST_CASE("the natural one-liners compile: a temporary budget, an integral time") {
  const auto arm = models::robot_arm();
  std::array<double, 2> x{0.5, 0.0}, dx;
  const auto sys = checked(arm, budget{.max_rhs_evals = 3});
  auto copy = sys;  // Odeint copies systems: the copies share one budget
  sys(x, dx, 0.0);
  copy(x, dx, 0.0);
  sys(x, dx, 0.0);
  CHECK(sys.b->rhs_evals == 3);
  CHECK_THROWS_WITH(copy(x, dx, 0.0), Contains("the budget of 3 derivative evaluations is spent"));
  const auto sol = recover(arm, 0, x);  // 0, not 0.0
  CHECK(sol.t == 0.0);
  CHECK(sol.energy() == recover(arm, 0.0, x).energy());
}
