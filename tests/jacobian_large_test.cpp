// The Jacobian of a scene too large for Eigen's fixed-size matrices: a
// floating trunk with eight legs of eight joints (models::legged<8, 8>, 64
// joints, 70 rates, 141 states), whose 141 × 141 Jacobian (159 KB) is past
// EIGEN_STACK_ALLOCATION_LIMIT (128 KB: 128 states). Its jacobian_matrix is
// sized at run time; the analytic passes fill it, checked against central
// differences to their accuracy (dual numbers over 141 states cost minutes
// to compile); jacobian() into a matrix made before allocates nothing, the
// returned form once.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/legged.hpp>
#include <flange/simulate/jacobian.hpp>

#include "allocation_counter.hpp"

namespace flange::test {
namespace {

auto tree_state() {
  const auto s = models::legged<8, 8>();
  auto x = neutral_state(s);
  for (int i = 0; i < decltype(s)::n_state; ++i) x[i] += 0.1 * std::sin(1.3 * i + 0.4);
  normalize(s, x);
  return x;
}

using tree = std::remove_cvref_t<decltype(models::legged<8, 8>())>;
using chain64 = std::remove_cvref_t<decltype(models::chain<64, models::runtime_axes>({}))>;
static_assert(tree::n_state == 141);
static_assert(!detail::jacobian_on_stack<tree>() && std::is_same_v<jacobian_matrix<tree>, Eigen::MatrixXd>);
static_assert(detail::jacobian_on_stack<chain64>() && jacobian_matrix<chain64>::RowsAtCompileTime == 128,
              "128 states still fit on the stack");

TEST_CASE("a 64-joint floating tree's Jacobian (141 states) is sized at run time and equals central differences") {
  const auto s = models::legged<8, 8>();
  const auto x = tree_state();
  const double t = 0.3;
  Eigen::Matrix<double, tree::n_state, 1> ft, ft_fd;
  const auto J = jacobian(s, t, x, &ft);
  REQUIRE(J.rows() == tree::n_state);
  REQUIRE(J.cols() == tree::n_state);
  CHECK(J.allFinite());
  const auto J_fd = jacobian_finite_difference(s, t, x, &ft_fd);
  // h = ε^(1/3): about 1e-10 relative, so 1e-7 of the largest entry
  // (jacobian_agree.hpp's bar).
  const double scale = std::max(1.0, J_fd.cwiseAbs().maxCoeff());
  INFO("largest entry " << scale);
  CHECK((J - J_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  CHECK((ft - ft_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
  // The leg joints' q̇ = v: their rows land in place (the trunk's 7
  // coordinates first, then joint k's, k = 0 … 63, whose rate is 6 + k).
  for (int k = 0; k < 64; ++k) CHECK(J(7 + k, tree::n_q + 6 + k) == 1.0);
}

TEST_CASE("jacobian() into a matrix made before allocates nothing on a 141-state tree, the returned form once") {
  const auto s = models::legged<8, 8>();
  const auto x = tree_state();
  auto J = make_jacobian_matrix<tree>();
  jacobian(s, 0.0, x, J);
  const auto J1 = J;
  CHECK(count_allocations([&] { jacobian(s, 0.0, x, J); }) == 0);
  CHECK(J == J1);
  long made = 0;
  CHECK(count_allocations([&] { made += jacobian(s, 0.0, x).rows(); }) == 1);
  CHECK(made == tree::n_state);
}

}  // namespace
}  // namespace flange::test
