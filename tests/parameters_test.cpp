// Bad parameters throw at construction, naming the component and the value;
// a singularity found during simulation throws with the time and the state.
#include <limits>

#include <catch2/catch.hpp>
#include <flange/flange.hpp>

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

TEST_CASE("joints refuse a zero or non-finite axis") {
  CHECK_THROWS_WITH(Revolute<"elbow">({.n = {0, 0, 0}}), Contains("Revolute \"elbow\"") && Contains("length 0"));
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
  CHECK_THROWS_WITH(chain(x, dx, 0.0), Contains("joint \"j1\" (q[1])"));
}
