// The articulated body's known zeros (dynamics/articulated_body.hpp,
// known_zero_dims): behind a joint of one rate along a coordinate direction,
// I_a·S = 0 makes rows of the articulated inertia zero, which the step up
// sets instead of computing, skips as factors and keeps out of the turn
// about the joint's own axis. The path runs only for a link with a parent
// link (a root link passes nothing up), so these scenes put every kind of
// such joint in series: revolute and prismatic, typed and run-time axes, in
// space and in a plane, with offsets, centre-of-mass offsets and full
// inertias. Checked against Newton–Euler with the mass matrix, which shares
// none of those passes, in both forms of the articulated body's steps
// (unrolled and shared).
#include <catch2/catch.hpp>
#include <flange/dynamics/forward_dynamics.hpp>
#include <flange/equations_of_motion.hpp>

#include "aba_agreement.hpp"

#include <random>

using namespace flange;

namespace {

Body<"b1", cm::offset> body1() {
  return Body<"b1", cm::offset>({.m = 1.3, .J = Vec3d(0.02, 0.03, 0.025).asDiagonal(), .r_cm = {0.1, 0.02, -0.03}});
}

/// Revolute (z), prismatic (y), revolute (run-time axis), prismatic (run-time
/// axis), revolute (x), each hanging from the previous body.
auto spatial_mixed() {
  Mat3d J = Vec3d(0.04, 0.05, 0.03).asDiagonal();
  J(0, 1) = J(1, 0) = 0.004;
  J(1, 2) = J(2, 1) = -0.003;
  return scene(World<"world">{}, Revolute<"r1", axis::z>{}, body1(), FixedTranslation<"t1">({.d = {0.3, 0.05, 0.1}}),
               Prismatic<"p1", axis::y>({}), Body<"b2", cm::offset>({.m = 0.8, .J = J, .r_cm = {0.0, 0.1, 0.05}}),
               FixedTranslation<"t2">({.d = {0.2, -0.1, 0.15}}), Revolute<"r2">({.n = Vec3d(1, 2, 2).normalized()}),
               Body<"b3", cm::offset>({.m = 1.1, .J = 1.5 * J, .r_cm = {0.12, 0.0, -0.04}}),
               Prismatic<"p2">({.n = Vec3d(-2, 1, 2).normalized()}),
               Body<"b4", cm::offset>({.m = 0.6, .J = 0.7 * J, .r_cm = {-0.05, 0.08, 0.02}}),
               FixedTranslation<"t3">({.d = {0.1, 0.25, -0.05}}), Revolute<"r3", axis::x>{},
               Body<"b5", cm::offset>({.m = 0.9, .J = J, .r_cm = {0.07, -0.06, 0.11}}),
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">,
               connect<"r1.frame_b", "t1.frame_a">, connect<"t1.frame_b", "p1.frame_a">,
               connect<"p1.frame_b", "b2.frame_a">, connect<"p1.frame_b", "t2.frame_a">,
               connect<"t2.frame_b", "r2.frame_a">, connect<"r2.frame_b", "b3.frame_a">,
               connect<"r2.frame_b", "p2.frame_a">, connect<"p2.frame_b", "b4.frame_a">,
               connect<"p2.frame_b", "t3.frame_a">, connect<"t3.frame_b", "r3.frame_a">,
               connect<"r3.frame_b", "b5.frame_a">);
}

/// Revolute, prismatic along x, prismatic along y, revolute, all in the
/// plane z = 0: computed in planar arithmetic.
auto planar_mixed() {
  return scene(World<"world">{}, Revolute<"r1", axis::z>{}, body1(), FixedTranslation<"t1">({.d = {0.3, 0.05, 0}}),
               Prismatic<"px", axis::x>({}), Body<"b2">({.m = 0.8, .J = Mat3d::Identity() * 0.03}),
               Prismatic<"py", axis::y>({}),
               Body<"b3", cm::offset>({.m = 1.1, .J = Mat3d::Identity() * 0.05, .r_cm = {0.1, 0.05, 0}}),
               FixedTranslation<"t2">({.d = {0.2, -0.1, 0}}), Revolute<"r2", axis::z>{},
               Body<"b4", cm::offset>({.m = 0.6, .J = Mat3d::Identity() * 0.02, .r_cm = {0.15, 0, 0}}),
               connect<"world.frame_b", "r1.frame_a">, connect<"r1.frame_b", "b1.frame_a">,
               connect<"r1.frame_b", "t1.frame_a">, connect<"t1.frame_b", "px.frame_a">,
               connect<"px.frame_b", "b2.frame_a">, connect<"px.frame_b", "py.frame_a">,
               connect<"py.frame_b", "b3.frame_a">, connect<"py.frame_b", "t2.frame_a">,
               connect<"t2.frame_b", "r2.frame_a">, connect<"r2.frame_b", "b4.frame_a">);
}

constexpr double round_off = test::aba_round_off;

}  // namespace

TEST_CASE("every joint kind the known zeros cover, in series in space, agrees with Newton–Euler + M") {
  const auto s = spatial_mixed();
  using S = std::remove_cvref_t<decltype(s)>;
  // The links behind p1, r2, p2 and r3 take the known-zero path: one rate
  // each, along a coordinate direction of its (axis-framed) link.
  STATIC_REQUIRE(S::n_v == 5);
  const double w = test::worst_aba_disagreement(s, 5, 50);
  INFO("worst |Δv̇| / max|v̇| = " << w);
  CHECK(w < round_off);
}

TEST_CASE("revolute and prismatic joints in series in a plane agree with Newton–Euler + M") {
  const auto s = planar_mixed();
  using S = std::remove_cvref_t<decltype(s)>;
  STATIC_REQUIRE(detail::planar_axis<S>() == 2);
  const double w = test::worst_aba_disagreement(s, 5, 50);
  INFO("worst |Δv̇| / max|v̇| = " << w);
  CHECK(w < round_off);
}
