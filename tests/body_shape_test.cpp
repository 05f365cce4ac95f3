// BodyBox and BodyCylinder (Modelica's): mass and inertia against their
// closed forms, and a spatial double pendulum built from them against the
// same pendulum written as FixedTranslation + Body<cm::offset>: derivatives,
// recovered cut forces, the residual and the energy along a trajectory.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <boost/numeric/odeint.hpp>

#include <flange/flange.hpp>

using namespace flange;
namespace odeint = boost::numeric::odeint;

namespace {

const Vec3d r_box(0.6, 0.0, 0.2);
const Vec3d r_cyl(0.0, -0.5, 0.1);

auto shaped() {
  return scene(World<"world">({.g = {0, 0, -9.81}}), Revolute<"j1", axis::x>(), Revolute<"j2">({.n = {0, 1, 1}}),
               BodyBox<"box">({.r = r_box, .width = 0.05, .height = 0.03, .width_direction = {0, 1, 1}}),
               BodyCylinder<"tube">({.r = r_cyl, .diameter = 0.04, .inner_diameter = 0.03, .density = 2700}),
               connect<"world.frame_b", "j1.frame_a">, connect<"j1.frame_b", "box.frame_a">,
               connect<"box.frame_b", "j2.frame_a">, connect<"j2.frame_b", "tube.frame_a">);
}

/// The same pendulum with each shaped body as a Body at frame_a (centre of
/// mass offset) plus a FixedTranslation to the next joint.
template <class Box, class Cyl>
auto plain(const Box& box, const Cyl& tube) {
  return scene(World<"world">({.g = {0, 0, -9.81}}), Revolute<"j1", axis::x>(), Revolute<"j2">({.n = {0, 1, 1}}),
               Body<"box", cm::offset>({.m = box.m(), .J = box.J(), .r_cm = box.r_cm()}),
               FixedTranslation<"box_len">({.d = box.r()}),
               Body<"tube", cm::offset>({.m = tube.m(), .J = tube.J(), .r_cm = tube.r_cm()}),
               connect<"world.frame_b", "j1.frame_a">, connect<"j1.frame_b", "box.frame_a">,
               connect<"j1.frame_b", "box_len.frame_a">, connect<"box_len.frame_b", "j2.frame_a">,
               connect<"j2.frame_b", "tube.frame_a">);
}

}  // namespace

TEST_CASE("a BodyBox's mass and inertia are the box's closed forms, turned along its length") {
  const double l = r_box.norm(), w = 0.05, h = 0.03, m = 7700 * l * w * h;
  const BodyBox<"box"> box({.r = r_box, .width = w, .height = h});
  CHECK(box.m() == Approx(m).epsilon(1e-15));
  CHECK((box.r_cm() - r_box / 2).norm() == 0.0);
  const Vec3d ex = r_box.normalized();
  // Along the length: m·(w² + h²)/12; the width direction (default y) is
  // perpendicular to r here, so it is an axis too.
  CHECK((box.J() * ex - m * (w * w + h * h) / 12 * ex).norm() <= 1e-15 * m);
  const Vec3d ey(0, 1, 0);
  CHECK((box.J() * ey - m * (l * l + h * h) / 12 * ey).norm() <= 1e-15 * m);
  const Vec3d ez = ex.cross(ey);
  CHECK((box.J() * ez - m * (l * l + w * w) / 12 * ez).norm() <= 1e-15 * m);
  // Modelica's defaults: width |r|/20, height = width.
  const BodyBox<"b"> d({.r = {2, 0, 0}});
  CHECK(d.size() == Vec3d(2, 0.1, 0.1));
  CHECK(d.m() == Approx(7700 * 2 * 0.1 * 0.1).epsilon(1e-15));
}

TEST_CASE("a BodyCylinder's mass and inertia are the tube's closed forms") {
  const double l = r_cyl.norm(), ro = 0.02, ri = 0.015, rho = 2700;
  const BodyCylinder<"tube"> tube({.r = r_cyl, .diameter = 2 * ro, .inner_diameter = 2 * ri, .density = rho});
  const double m = rho * std::numbers::pi * l * (ro * ro - ri * ri);
  CHECK(tube.m() == Approx(m).epsilon(1e-14));
  const Vec3d ex = r_cyl.normalized();
  CHECK((tube.J() * ex - m * (ro * ro + ri * ri) / 2 * ex).norm() <= 1e-14 * m);
  // Any axis across: m·(3·(ro² + ri²) + l²)/12.
  const Vec3d across = ex.cross(Vec3d(1, 0, 0)).normalized();
  CHECK((tube.J() * across - m * (3 * (ro * ro + ri * ri) + l * l) / 12 * across).norm() <= 1e-14 * m);
}

TEST_CASE("shaped bodies give the dynamics of the same bodies written as FixedTranslation + Body") {
  const auto a = shaped();
  const auto b = plain(a.get<"box">(), a.get<"tube">());
  using A = decltype(a);
  static_assert(A::n_equations == A::n_unknowns);
  static_assert(decltype(b)::n_equations == decltype(b)::n_unknowns);
  for (int k = 0; k < 25; ++k) {
    const A::state_type x{0.3 * k - 3, std::sin(1.7 * k), 0.4 * std::cos(k), -1.0 + 0.1 * k};
    A::state_type da, db;
    a(x, da, 0.0);
    b(x, db, 0.0);
    for (int i = 0; i < 4; ++i) CHECK(std::abs(da[i] - db[i]) <= 1e-13 * (1 + std::abs(db[i])));
    // Recovery: the cut forces at the joints agree, and the residual holds.
    const auto sa = recover(a, 0.0, x);
    const auto sb = recover(b, 0.0, x);
    for (const char* f : {"j1.frame_a", "j1.frame_b", "j2.frame_a", "j2.frame_b", "world.frame_b"}) {
      CHECK((sa.cut_at(f).f - sb.cut_at(f).f).norm() <= 1e-12 * (1 + sb.cut_at(f).f.norm()));
      CHECK((sa.cut_at(f).n - sb.cut_at(f).n).norm() <= 1e-12 * (1 + sb.cut_at(f).n.norm()));
    }
    CHECK(scaled_residual(a, sa) <= 1e-13);
    CHECK(sa.energy() == Approx(sb.energy()).epsilon(1e-13));
  }
}

TEST_CASE("a double pendulum of shaped bodies conserves its energy") {
  const auto a = shaped();
  using A = decltype(a);
  A::state_type x{1.0, 0.0, -0.5, 2.0};
  const double e0 = recover(a, 0.0, x).energy();
  odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_dopri5<A::state_type>>(1e-12, 1e-12), a, x,
                             0.0, 5.0, 1e-3);
  const double e1 = recover(a, 5.0, x).energy();
  CHECK(std::abs(e1 - e0) <= 1e-8 * std::abs(e0));
}

TEST_CASE("bad shapes are refused at construction, naming the body and the value") {
  CHECK_THROWS_WITH(BodyBox<"slab">({.r = Vec3d::Zero()}), Catch::Contains("BodyBox \"slab\"") && Catch::Contains("no length"));
  CHECK_THROWS_WITH(BodyBox<"slab">({.r = {1, 0, 0}, .density = -1}), Catch::Contains("density -1"));
  CHECK_THROWS_WITH(BodyCylinder<"pipe">({.r = {1, 0, 0}, .diameter = 0.1, .inner_diameter = 0.2}),
                    Catch::Contains("BodyCylinder \"pipe\"") && Catch::Contains("inner diameter 0.2"));
  CHECK_THROWS_WITH(BodyBox<"slab">({.r = {1, 0, 0}, .width = -0.1}), Catch::Contains("width -0.1"));
}
