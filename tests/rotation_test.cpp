// The paper's rotation conventions, checked on random inputs against
// properties and against Eigen's independent AngleAxis (active rotation).
#include <random>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <flange/detail/static_for.hpp>
#include <flange/math/congruence.hpp>
#include <flange/math/rotation.hpp>

using namespace flange;
using Catch::Matchers::WithinAbs;

namespace {
std::mt19937 rng(20261122);
Vec3d random_unit() {
  std::normal_distribution<double> n;
  return Vec3d(n(rng), n(rng), n(rng)).normalized();
}
double random_angle() { return std::uniform_real_distribution<double>(-10, 10)(rng); }
constexpr double eps = 1e-14;  // a few ulps of the O(1) entries involved
}  // namespace

TEST_CASE("axis rotation is orthogonal with determinant one and keeps its axis") {
  for (int i = 0; i < 500; ++i) {
    const Vec3d n = random_unit();
    const double phi = random_angle();
    const Mat3d R = axis_rotation<double>(n, phi);
    CHECK((R * R.transpose() - Mat3d::Identity()).cwiseAbs().maxCoeff() < 4 * eps);
    CHECK_THAT(R.determinant(), WithinAbs(1.0, 4 * eps));
    CHECK((R * n - n).cwiseAbs().maxCoeff() < 4 * eps);
  }
}

TEST_CASE("axis rotation is the transpose of the active rotation (Eigen AngleAxis)") {
  for (int i = 0; i < 500; ++i) {
    const Vec3d n = random_unit();
    const double phi = random_angle();
    const Mat3d active = Eigen::AngleAxisd(phi, n).toRotationMatrix();
    CHECK((axis_rotation<double>(n, phi) - active.transpose()).cwiseAbs().maxCoeff() < 8 * eps);
  }
}

TEST_CASE("two rotations about one axis compose by adding angles") {
  for (int i = 0; i < 500; ++i) {
    const Vec3d n = random_unit();
    const double a = random_angle(), b = random_angle();
    const Mat3d lhs = axis_rotation<double>(n, a) * axis_rotation<double>(n, b);
    CHECK((lhs - axis_rotation<double>(n, a + b)).cwiseAbs().maxCoeff() < 16 * eps);
  }
}

TEST_CASE("tilde is the cross product and vex inverts it") {
  for (int i = 0; i < 500; ++i) {
    const Vec3d a = random_unit() * 3, b = random_unit() * 2;
    CHECK((tilde<double>(a) * b - a.cross(b)).cwiseAbs().maxCoeff() < 8 * eps);
    CHECK((vex<double>(tilde<double>(a)) - a).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("omega from R·Ṙ' matches a finite difference of R(t)") {
  // R(t) = R_b(β(t))·R_a(α(t)): frame b turned about n_b relative to frame a,
  // itself turned about n_a. In frame coordinates ω = n_b·β̇ + R_b·n_a·α̇.
  for (int i = 0; i < 200; ++i) {
    const Vec3d na = random_unit(), nb = random_unit();
    const double a0 = random_angle(), b0 = random_angle(), ad = random_angle(), bd = random_angle();
    auto R = [&](double t) { return Mat3d(axis_rotation<double>(nb, b0 + bd * t) * axis_rotation<double>(na, a0 + ad * t)); };
    const double h = 1e-5;
    const Mat3d Rdot = (R(h) - R(-h)) / (2 * h);
    const Vec3d w = omega_from<double>(R(0), Rdot);
    const Vec3d expected = nb * bd + axis_rotation<double>(nb, b0) * na * ad;
    // Central difference: truncation h²/6·|R'''| ≤ h²/6·(|ad|+|bd|)³ ≈ 1.5e-7 at
    // worst here, rounding ε/h ≈ 1e-11.
    const double tol = h * h / 6 * std::pow(std::abs(ad) + std::abs(bd), 3) + 1e-10;
    CHECK((w - expected).cwiseAbs().maxCoeff() < tol);
  }
}

TEST_CASE("the orientation residue is zero for equal rotations and the small angle otherwise") {
  for (int i = 0; i < 200; ++i) {
    const Mat3d R = axis_rotation<double>(random_unit(), random_angle());
    CHECK(orientation_residue<double>(R, R).cwiseAbs().maxCoeff() < 4 * eps);
    // R1 = R_rel(δ about e_k)·R2: the residue is ≈ −δ·e_k (passive convention),
    // with an O(δ²) error.
    for (int k = 0; k < 3; ++k) {
      const double delta = 1e-4;
      const Vec3d r = orientation_residue<double>(axis_rotation<double>(Vec3d::Unit(k), delta) * R, R);
      CHECK((r + delta * Vec3d::Unit(k)).cwiseAbs().maxCoeff() < delta * delta);
    }
  }
}

// Eᵀ·X·E for the typed rotations an axis frame turns by (math/congruence.hpp):
// a (c, s) pair about each coordinate axis, and the product R_z·R_x of two,
// against dense products with Eigen's AngleAxis (a coordinate rotation is the
// transpose of the active one). The symmetric form computes 6 entries of the
// upper triangle from X's upper triangle; the general one every entry.
TEST_CASE("congruence by coordinate rotations and their products equals the dense Eᵀ·X·E") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    Mat3d G;
    for (int i = 0; i < 9; ++i) G.data()[i] = u(rng);
    const Mat3d X = G + G.transpose();
    const double a = 3 * u(rng), b = 3 * u(rng);
    const auto passive = [](double phi, int axis) -> Mat3d {
      return Eigen::AngleAxisd(phi, Vec3d::Unit(axis)).toRotationMatrix().transpose();
    };
    const auto near = [](const Mat3d& y, const Mat3d& ref) { return (y - ref).cwiseAbs().maxCoeff() <= 1e-14; };
    flange::detail::static_for<3>([&](auto I) {
      const flange::coordinate_rotation<double, I> E{std::cos(a), std::sin(a)};
      const Mat3d D = passive(a, I);
      CHECK(near(flange::rotated_back_sym<double>(E, X), D.transpose() * X * D));
      CHECK(near(flange::rotated_back<double>(E, G), D.transpose() * G * D));
    });
    const flange::rotation_product<flange::coordinate_rotation<double, 2>, flange::coordinate_rotation<double, 0>> P{
        {std::cos(a), std::sin(a)}, {std::cos(b), std::sin(b)}};
    const Mat3d D = passive(a, 2) * passive(b, 0);
    CHECK(near(flange::rotated_back_sym<double>(P, X), D.transpose() * X * D));
    CHECK(near(flange::rotated_back<double>(P, G), D.transpose() * G * D));
    CHECK(near(flange::to_matrix<double>(P), D));
    // With row and column Z of X known zero (row Z of G): every coordinate
    // rotation skips them (about Z it keeps them zero, about another axis
    // it turns them out of place), and the product passes them on from its
    // first factor about Z to the second.
    flange::detail::static_for<3>([&](auto Z) {
      Mat3d Xz = X, Gz = G;
      Xz.row(Z).setZero();
      Xz.col(Z).setZero();
      Gz.row(Z).setZero();
      flange::detail::static_for<3>([&](auto I) {
        const flange::coordinate_rotation<double, I> E{std::cos(a), std::sin(a)};
        const Mat3d DI = passive(a, I);
        CHECK(near(flange::rotated_back_sym<double, Z>(E, Xz), DI.transpose() * Xz * DI));
        CHECK(near(flange::rotated_back<double, Z>(E, Gz), DI.transpose() * Gz * DI));
      });
      const flange::rotation_product<flange::coordinate_rotation<double, Z>, flange::coordinate_rotation<double, (Z + 1) % 3>>
          Q{{std::cos(a), std::sin(a)}, {std::cos(b), std::sin(b)}};
      const Mat3d DQ = passive(a, Z) * passive(b, (Z + 1) % 3);
      CHECK(near(flange::rotated_back_sym<double, Z>(Q, Xz), DQ.transpose() * Xz * DQ));
      CHECK(near(flange::rotated_back<double, Z>(Q, Gz), DQ.transpose() * Gz * DQ));
    });
  }
}
