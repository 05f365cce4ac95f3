// Joints by name: inputs read q<"elbow">(x) and v<"elbow">(x) resolved at
// compile time, initial states written by name with every other joint at
// its neutral configuration, recovered internals through the free
// internal<"component", "variable">(sol). Each is checked against the same
// thing done by position, which must agree exactly.
#include <catch2/catch.hpp>

#include <cmath>

#include <flange/equations_of_motion.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>

using namespace flange;

namespace {

// A user's own names beside `using namespace flange;`: the diagnostic tags
// (constraints, rates, member, unknowns, …) live in flange::diagnostic, so
// these are not ambiguous.
int constraints() { return 3; }
int rates() { return 2; }
struct member {
  int id = 7;
};

/// A slender link of mass m and length l, its centre of mass halfway along x.
template <fixed_string Name>
Body<Name, cm::offset> link(double m, double l) {
  return Body<Name, cm::offset>({.m = m, .J = (Vec3d(0.1, 1.0, 1.0) * (m * l * l / 12)).asDiagonal(),
                                 .r_cm = Vec3d(l / 2, 0, 0)});
}

/// A 3-joint spatial arm (shoulder about z, elbow and wrist about y), each
/// joint driven by the torque law tau_<k>.
template <class T0, class T1, class T2>
auto arm3(T0 t0, T1 t1, T2 t2) {
  return scene(World<"world">({.g = {0, 0, -9.81}}), revolute<"shoulder", axis::z>(t0),
               revolute<"elbow", axis::y>(t1), revolute<"wrist", axis::y>(t2),
               link<"upper">(2.0, 0.5), FixedTranslation<"upper_len">({.d = {0.5, 0, 0}}),
               link<"fore">(1.0, 0.4), FixedTranslation<"fore_len">({.d = {0.4, 0, 0}}),
               link<"hand">(0.5, 0.1),  //
               connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
               connect<"shoulder.frame_b", "upper_len.frame_a">, connect<"upper_len.frame_b", "elbow.frame_a">,
               connect<"elbow.frame_b", "fore.frame_a">, connect<"elbow.frame_b", "fore_len.frame_a">,
               connect<"fore_len.frame_b", "wrist.frame_a">, connect<"wrist.frame_b", "hand.frame_a">);
}

}  // namespace

TEST_CASE("inputs that read joints by name equal the same inputs by position") {
  auto by_name_s = [](auto, const auto& x) { return 8.0 * (0.5 - q<"shoulder">(x)) - 2.0 * v<"shoulder">(x); };
  auto by_name_e = [](auto, const auto& x) { return 6.0 * (0.3 - q<"elbow">(x)) - 1.0 * v<"elbow">(x); };
  auto by_name_w = [](auto, const auto& x) { return 2.0 * (q<"elbow">(x) - q<"wrist">(x)) - 0.5 * v<"wrist">(x); };
  auto by_pos_s = [](auto, const auto& x) { return 8.0 * (0.5 - x.q(0)) - 2.0 * x.v(0); };
  auto by_pos_e = [](auto, const auto& x) { return 6.0 * (0.3 - x.q(1)) - 1.0 * x.v(1); };
  auto by_pos_w = [](auto, const auto& x) { return 2.0 * (x.q(1) - x.q(2)) - 0.5 * x.v(2); };
  const auto named = arm3(by_name_s, by_name_e, by_name_w);
  const auto positional = arm3(by_pos_s, by_pos_e, by_pos_w);
  using A = decltype(named);
  static_assert(A::n_equations == A::n_unknowns);
  for (int k = 0; k < 20; ++k) {
    A::state_type x{0.1 * k, -0.05 * k, 0.3 - 0.02 * k, 0.2, -0.1 * k, 0.05 * k}, a, b;
    named(x, a, 0.0);
    positional(x, b, 0.0);
    CHECK(a == b);
    // The member form, as a non-generic caller writes it.
    const auto view = state_view<A>(x.data(), x.data() + A::n_q);
    CHECK(view.q<"wrist">() == x[2]);
    CHECK(view.v<"elbow">() == x[4]);
  }
  // The same through the dual-number Jacobian: the name resolves for any scalar.
  const A::state_type x{0.2, 0.1, -0.3, 0.5, 0.0, -0.4};
  const auto Ja = jacobian(named, 0.0, x), Jb = jacobian(positional, 0.0, x);
  CHECK(Ja == Jb);
}

TEST_CASE("a multi-coordinate joint's name gives its coordinates and rates") {
  const auto top = scene(World<"world">({.g = {0, 0, -9.81}}), Spherical<"ball">(), Prismatic<"slide", axis::x>({}),
                         Body<"a">({.m = 1, .J = Mat3d::Identity()}), Body<"b">({.m = 2, .J = Mat3d::Identity()}),
                         connect<"world.frame_b", "ball.frame_a">, connect<"ball.frame_b", "a.frame_a">,
                         connect<"ball.frame_b", "slide.frame_a">, connect<"slide.frame_b", "b.frame_a">);
  using S = decltype(top);
  const auto x = initial_state<"ball", "slide">(
      top, {.R = orientation::axis_angle(Vec3d(1, 1, 0).normalized(), 0.4), .w = {0.1, 0.2, 0.3}},
      {.q = 0.25, .v = -1.5});
  const auto view = state_view<S>(x.data(), x.data() + S::n_q);
  const Eigen::Vector4d quat = q<"ball">(view);
  const Eigen::Vector3d w = v<"ball">(view);
  CHECK(quat.norm() == Approx(1.0).epsilon(1e-15));
  for (int i = 0; i < 4; ++i) CHECK(quat[i] == x[S::q_offset("ball") + i]);
  for (int i = 0; i < 3; ++i) CHECK(w[i] == x[S::n_q + S::v_offset("ball") + i]);
  CHECK(w == Eigen::Vector3d(0.1, 0.2, 0.3));
  CHECK(q<"slide">(view) == 0.25);
  CHECK(v<"slide">(view) == -1.5);
  // The former name of the rates still reads them, deprecated for one release.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  CHECK(qd<"slide">(view) == -1.5);
  CHECK(view.qd(S::v_offset<"slide">()) == -1.5);
#pragma GCC diagnostic pop
}

TEST_CASE("initial_state sets the named joints and leaves the others neutral and at rest") {
  const auto arm = arm3(0.0, 0.0, 0.0);
  using A = decltype(arm);
  const auto x = initial_state<"elbow">(arm, {.q = 0.7, .v = -2.0});
  CHECK(x == A::state_type{0, 0.7, 0, 0, -2.0, 0});
  // Equal to set_joint one by one, in any order.
  auto y = neutral_state(arm);
  set_joint<"wrist">(arm, y, {.q = -0.1, .v = 0.5});
  set_joint<"shoulder">(arm, y, {.q = 1.2});
  CHECK(initial_state<"shoulder", "wrist">(arm, {.q = 1.2}, {.q = -0.1, .v = 0.5}) == y);
  CHECK(initial_state<"wrist", "shoulder">(arm, {.q = -0.1, .v = 0.5}, {.q = 1.2}) == y);
  // Values are still checked at run time.
  CHECK_THROWS_WITH(initial_state<"elbow">(arm, {.q = std::nan("")}),
                    Catch::Contains("elbow") && Catch::Contains("not finite"));
}

TEST_CASE("a quaternion joint left out of initial_state is the identity, not zeros") {
  const auto body = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"free">(), Revolute<"hinge", axis::z>(),
                          Body<"a">({.m = 1, .J = Mat3d::Identity()}), Body<"b">({.m = 1, .J = Mat3d::Identity()}),
                          connect<"world.frame_b", "free.frame_a">, connect<"free.frame_b", "a.frame_a">,
                          connect<"free.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "b.frame_a">);
  using S = decltype(body);
  const auto x = initial_state<"hinge">(body, {.q = 0.3});
  const int o = S::q_offset("free");
  // The position (3), then the quaternion (x, y, z, w) = (0, 0, 0, 1).
  CHECK(x[o + 3] == 0.0);
  CHECK(x[o + 6] == 1.0);
  CHECK(x[S::q_offset("hinge")] == 0.3);
}

TEST_CASE("get_joint reads back what set_joint wrote, for every kind of state") {
  const auto s = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"free">(), Revolute<"hinge", axis::z>(),
                       Spherical<"ball">(), Universal<"cardan">({.n_a = {1, 0, 0}, .n_b = {0, 1, 0}}),
                       Body<"a">({.m = 1, .J = Mat3d::Identity()}), Body<"b">({.m = 1, .J = Mat3d::Identity()}),
                       Body<"c">({.m = 1, .J = Mat3d::Identity()}), Body<"d">({.m = 1, .J = Mat3d::Identity()}),
                       connect<"world.frame_b", "free.frame_a">, connect<"free.frame_b", "a.frame_a">,
                       connect<"a.frame_a", "hinge.frame_a">, connect<"hinge.frame_b", "b.frame_a">,
                       connect<"b.frame_a", "ball.frame_a">, connect<"ball.frame_b", "c.frame_a">,
                       connect<"c.frame_a", "cardan.frame_a">, connect<"cardan.frame_b", "d.frame_a">);
  const Mat3d R = orientation::cardan(0.3, -0.2, 0.5).R, Rb = orientation::rpy(0.1, 0.7, -0.4).R;
  const auto x = initial_state<"free", "hinge", "ball", "cardan">(
      s, {.r = {1, 2, 3}, .v = {0.5, -1, 2}, .R = orientation::matrix(R), .w = {1, -2, 0.5}}, {.q = 0.3, .v = -4},
      {.R = orientation::matrix(Rb), .w = {0.1, 0.2, 0.3}}, {.q = {0.4, -0.6}, .v = {7, 8}});
  const auto f = get_joint<"free">(s, x);
  CHECK(f.r == Vec3d(1, 2, 3));
  CHECK(f.v == Vec3d(0.5, -1, 2));
  CHECK((f.R.R - R).cwiseAbs().maxCoeff() < 1e-15);  // through the unit quaternion
  CHECK(f.w == Vec3d(1, -2, 0.5));
  const auto h = get_joint<"hinge">(s, x);
  CHECK((h.q == 0.3 && h.v == -4));
  const auto b = get_joint<"ball">(s, x);
  CHECK((b.R.R - Rb).cwiseAbs().maxCoeff() < 1e-15);
  CHECK(b.w == Vec3d(0.1, 0.2, 0.3));
  const auto u = get_joint<"cardan">(s, x);
  CHECK((u.q[0] == 0.4 && u.q[1] == -0.6 && u.v[0] == 7 && u.v[1] == 8));
}

TEST_CASE("using namespace flange leaves a user's constraints(), rates() and member unambiguous") {
  CHECK(constraints() + rates() + member{}.id == 12);
}

TEST_CASE("q_offset and v_offset: by a checked name at compile time, or at run time with did-you-mean") {
  const auto body = scene(World<"world">({.g = {0, 0, 0}}), FreeMotion<"free">(), Revolute<"hinge", axis::z>(),
                          Body<"a">({.m = 1, .J = Mat3d::Identity()}), Body<"b">({.m = 1, .J = Mat3d::Identity()}),
                          connect<"world.frame_b", "free.frame_a">, connect<"free.frame_b", "a.frame_a">,
                          connect<"free.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "b.frame_a">);
  using S = decltype(body);
  static_assert(S::q_offset<"free">() == 0 && S::q_offset<"hinge">() == 7);
  static_assert(S::v_offset<"free">() == 0 && S::v_offset<"hinge">() == 6);
  static_assert(S::q_offset("hinge") == S::q_offset<"hinge">());
  CHECK_THROWS_WITH(S::q_offset("hinje"), Catch::Contains("no joint named \"hinje\"; did you mean \"hinge\"?"));
  CHECK_THROWS_WITH(S::v_offset("a"), Catch::Contains("no joint named \"a\""));  // a body, not a joint
  // A cut joint has no coordinates in the state, and says so.
  const auto fb = models::fourbar({});
  CHECK_THROWS_WITH(decltype(fb)::q_offset("rocker_pivot"),
                    Catch::Contains("\"rocker_pivot\" closes a loop and is cut") && Catch::Contains("recover"));
  CHECK(decltype(fb)::q_offset("rocker_pin") == 2);
}

TEST_CASE("internal<\"component\", \"variable\">(sol) reads a recovered internal from a generic lambda") {
  const auto arm = arm3(0.0, 0.0, 0.0);
  const auto x = initial_state<"shoulder", "elbow">(arm, {.q = 0.4, .v = 1.0}, {.q = -0.2, .v = 0.3});
  const auto sol = recover(arm, 0.0, x);
  auto read = [](const auto& s) { return internal<"elbow", "φ">(s); };
  auto rate = [](const auto& s) { return internal_rate<"shoulder", "φ">(s); };
  CHECK(read(sol) == -0.2);
  CHECK(rate(sol) == 1.0);
  // Greek letters may be typed in ASCII: "phi" is φ, "w" is ω.
  CHECK(internal<"elbow", "phi">(sol) == -0.2);
  CHECK(sol.internal<"upper", "w">() == sol.internal<"upper", "ω">());
}
