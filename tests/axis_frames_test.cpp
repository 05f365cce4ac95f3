// Axis frames (dynamics/axis_frames.hpp): a link behind a joint with a
// run-time axis computes in coordinates turned so that the axis is z. The
// turn must change nothing but the cost: the accelerations equal those of
// the same mechanism written by hand with typed joints about z behind
// FixedRotations (which no rule turns), and every output of a turned scene
// (frames, cut forces) satisfies the components' equations.
#include <catch2/catch.hpp>
#include <flange/equations_of_motion.hpp>

#include "consistency.hpp"
#include "random_params.hpp"

using namespace flange;

namespace {
constexpr int N = 5;

/// A rotation taking n to e_z, built differently from the library's
/// (Rodrigues about n × e_z), so the hand-written chain shares nothing with it.
Mat3d to_z(const Vec3d& n) {
  const Vec3d k = n.cross(Vec3d::UnitZ());
  const double s = k.norm(), c = n.z();
  if (s < 1e-12) return c > 0 ? Mat3d::Identity() : Mat3d(Vec3d(1, -1, -1).asDiagonal());
  const Vec3d u = k / s;
  return Eigen::AngleAxisd(std::atan2(s, c), u).toRotationMatrix();
}

/// The chain of models::chain with each link in coordinates A_k (A_k·n_k =
/// e_z): FixedRotation A_k·A_{k−1}ᵀ, then a Revolute about z, the offset and
/// the body turned by A_k.
template <int... I, int... K>
auto by_hand(const models::chain_params<N>& p, std::integer_sequence<int, I...>, std::integer_sequence<int, K...>) {
  std::array<Mat3d, N + 1> A;  // A[0]: the World's; A[k + 1]: link k's
  A[0] = Mat3d::Identity();
  for (int k = 0; k < N; ++k) A[k + 1] = to_z(p.axis[k]);
  return scene(World<"world">({.g = p.g}),
               FixedRotation<indexed_name<"c", I>()>({.R = orientation{A[I + 1] * A[I].transpose()}})...,
               Revolute<indexed_name<"j", I>(), axis::z>{}...,
               FixedTranslation<indexed_name<"r", I>()>({.d = A[I + 1] * p.d[I]})...,
               Body<indexed_name<"b", I>()>({.m = p.m[I], .J = A[I + 1] * p.J[I] * A[I + 1].transpose()})...,
               connect<"world.frame_b", "c0.frame_a">,
               connect<indexed_name<"c", I>() + ".frame_b", indexed_name<"j", I>() + ".frame_a">...,
               connect<indexed_name<"j", I>() + ".frame_b", indexed_name<"r", I>() + ".frame_a">...,
               connect<indexed_name<"r", I>() + ".frame_b", indexed_name<"b", I>() + ".frame_a">...,
               connect<indexed_name<"r", K>() + ".frame_b", indexed_name<"c", K + 1>() + ".frame_a">...);
}
}  // namespace

TEST_CASE("a chain with run-time axes, turned to its axis frames, equals the same chain written about z by hand") {
  std::mt19937 rng(31);
  const auto p = test::chain_params<N>(rng);
  const auto turned = models::chain<N, models::runtime_axes>(p);
  const auto hand = by_hand(p, std::make_integer_sequence<int, N>{}, std::make_integer_sequence<int, N - 1>{});
  using S = std::remove_cvref_t<decltype(turned)>;
  using H = std::remove_cvref_t<decltype(hand)>;
  static_assert(detail::axis_framed<S, 1> && detail::axis_framed<S, N>, "every link of the chain is turned");
  static_assert(!detail::axis_frames<H>::any, "typed joints are never turned");
  for (int k = 0; k < 20; ++k) {
    S::state_type x, a;
    H::state_type b;
    for (auto& v : x) v = test::uniform(rng, -2, 2);
    turned(x, a, 0.0);
    hand(x, b, 0.0);
    // Two formulations of one mechanism: they differ by round-off, which
    // the chain's conditioning (masses 0.2–2, inertias down to 0.02) lifts
    // to a few 1e-14.
    for (int i = N; i < 2 * N; ++i) CHECK(std::abs(a[i] - b[i]) <= 1e-12 * (1 + std::abs(b[i])));
    std::array<double, N> aba;
    accelerations_articulated_body(turned, 0.0, x.data(), x.data() + N, aba.data());
    for (int i = 0; i < N; ++i) CHECK(std::abs(aba[i] - b[N + i]) <= 1e-12 * (1 + std::abs(b[N + i])));
  }
}

TEST_CASE("turned links keep every frame's pose and cut force: the residual vanishes on a branched scene") {
  // Run-time axes throughout; a FixedRotation inside link "a", a branch
  // (b and c hang from a), c connected backwards (frame_b toward the World),
  // and a torque between two turned links.
  const Mat3d J = Vec3d(0.02, 0.03, 0.04).asDiagonal();
  const auto s = scene(
      World<"world">{}, Revolute<"a">({.n = Vec3d(0.3, -0.2, 1).normalized()}),
      FixedRotation<"tilt">({.r = {0.4, 0.1, 0}, .R = orientation::axis_angle({1, 1, 0}, 0.7)}),
      Revolute<"b">({.n = Vec3d(1, 0.2, 0.1).normalized()}), Revolute<"c">({.n = Vec3d(-0.1, 1, 0.4).normalized()}),
      FixedTranslation<"ra">({.d = {0.2, 0, 0.1}}), FixedTranslation<"rb">({.d = {0.5, 0.1, 0}}),
      FixedTranslation<"rc">({.d = {0, 0.4, -0.1}}), Body<"ma">({.m = 1.5, .J = J}), Body<"mb">({.m = 0.7, .J = J}),
      Body<"mc">({.m = 0.9, .J = J}), Torque<"motor">({.M_ext = Vec3d(0.1, -0.3, 0.5)}),
      connect<"world.frame_b", "a.frame_a">, connect<"a.frame_b", "ra.frame_a">, connect<"ra.frame_b", "ma.frame_a">,
      connect<"a.frame_b", "tilt.frame_a">, connect<"tilt.frame_b", "b.frame_a">, connect<"tilt.frame_b", "c.frame_b">,
      connect<"b.frame_b", "rb.frame_a">, connect<"rb.frame_b", "mb.frame_a">, connect<"c.frame_a", "rc.frame_a">,
      connect<"rc.frame_b", "mc.frame_a">, connect<"ra.frame_b", "motor.frame_a">,
      connect<"rb.frame_b", "motor.frame_b">);
  using S = std::remove_cvref_t<decltype(s)>;
  static_assert(detail::axis_frames<S>::turned[1] && detail::axis_frames<S>::turned[2] &&
                detail::axis_frames<S>::turned[3]);
  std::mt19937 rng(32);
  test::consistency c;
  for (int k = 0; k < 30; ++k) {
    S::state_type x;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    c.sample(s, 0.0, x);
  }
  CHECK(c.orthogonality < 1e-14);
  CHECK(c.residual < 1e-12);
  CHECK(c.algorithms < 1e-12);
}

TEST_CASE("a link whose child turns by a typed rotation keeps its own frame") {
  // Turning "a" would make the frame "b" hangs on a general rotation of
  // a's coordinates, and b's 2-D arithmetic a 3 × 3 one: a stays unturned.
  const Mat3d J = Vec3d(0.02, 0.03, 0.04).asDiagonal();
  const auto s = scene(World<"world">{}, Revolute<"a">({.n = Vec3d(0.3, -0.2, 1).normalized()}),
                       Revolute<"b", axis::z>{}, FixedTranslation<"ra">({.d = {0.5, 0, 0}}),
                       FixedTranslation<"rb">({.d = {0.5, 0, 0}}), Body<"ma">({.m = 1.0, .J = J}),
                       Body<"mb">({.m = 1.0, .J = J}), connect<"world.frame_b", "a.frame_a">,
                       connect<"a.frame_b", "ra.frame_a">, connect<"ra.frame_b", "ma.frame_a">,
                       connect<"ra.frame_b", "b.frame_a">, connect<"b.frame_b", "rb.frame_a">,
                       connect<"rb.frame_b", "mb.frame_a">);
  using S = std::remove_cvref_t<decltype(s)>;
  static_assert(!detail::axis_frames<S>::any);
  std::mt19937 rng(33);
  test::consistency c;
  for (int k = 0; k < 10; ++k) {
    S::state_type x;
    for (auto& v : x) v = test::uniform(rng, -3, 3);
    c.sample(s, 0.0, x);
  }
  CHECK(c.residual < 1e-12);
}
