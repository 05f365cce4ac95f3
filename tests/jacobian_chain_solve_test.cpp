// The analytic Jacobian's two solves of M (dynamics/derivatives.hpp): its
// articulated-body factor (math/chain_solve.hpp), which long chains take,
// against its LTDL factor (math/tree_solve.hpp), which the other tests
// hold to the dual-number Jacobian, on short chains of every node kind; the
// long chains that take it against central differences and the scene's own
// derivative; and a singular M stopping it with the derivative's reason.
#include <catch2/catch.hpp>

#include <flange/models/chain.hpp>
#include <flange/models/legged.hpp>
#include <flange/simulate/jacobian.hpp>

#include "tree_laws.hpp"

using namespace flange;

namespace {

/// Both solves' rows and v̇ at three random states: equal to 1e-12 of the
/// largest entry (the bar jacobian_agree.hpp holds the LTDL solve's
/// rows to against dual numbers; these chains' M are well conditioned).
template <class S>
void solves_agree(const S& scene, std::mt19937& rng) {
  using rows = detail::derivative_rows<S>;
  for (int k = 0; k < 3; ++k) {
    const auto x = test::random_state(scene, rng);
    alignas(32) rows a, c;
    std::array<double, S::n_v> va, vc;
    test::poison_stack();
    REQUIRE(detail::acceleration_derivatives<S, true>(scene, 0.3, x.data(), x.data() + S::n_q, a, va.data()).index <
            0);
    test::poison_stack();
    REQUIRE(detail::acceleration_derivatives<S, false>(scene, 0.3, x.data(), x.data() + S::n_q, c, vc.data()).index <
            0);
    const auto A = a.template leftCols<2 * S::n_v + 1>(), Cv = c.template leftCols<2 * S::n_v + 1>();
    const double scale = std::max(1.0, Cv.cwiseAbs().maxCoeff());
    double largest = 1, dv = 0;
    for (int i = 0; i < S::n_v; ++i) {
      largest = std::max(largest, std::abs(vc[i]));
      dv = std::max(dv, std::abs(va[i] - vc[i]));
    }
    INFO("state " << k << ", largest entry " << scale);
    CHECK((A - Cv).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    CHECK(dv <= 1e-12 * largest);
  }
}

/// The Jacobian of a scene that takes the articulated-body factor against
/// central differences (1e-7 of the largest entry: jacobian_agree.hpp's
/// bar) and its v̇ against the scene's derivative (1e-12 of the largest).
template <class S>
void long_chain_agrees(const S& scene, std::mt19937& rng) {
  STATIC_REQUIRE(detail::articulated_solve<S>());
  for (int k = 0; k < 3; ++k) {
    const auto x = test::random_state(scene, rng);
    test::poison_stack();
    const auto J = jacobian(scene, 0.3, x);
    const auto J_fd = jacobian_finite_difference(scene, 0.3, x);
    const double scale = std::max(1.0, J_fd.cwiseAbs().maxCoeff());
    INFO("state " << k << ", largest entry " << scale);
    CHECK((J - J_fd).cwiseAbs().maxCoeff() <= 1e-7 * scale);
    std::array<double, S::n_state> xs, f;
    for (int i = 0; i < S::n_state; ++i) xs[i] = x[i];
    scene(xs, f, 0.3);
    alignas(32) detail::derivative_rows<S> rows;
    std::array<double, S::n_v> vdot;
    REQUIRE(detail::acceleration_derivatives(scene, 0.3, xs.data(), xs.data() + S::n_q, rows, vdot.data()).index < 0);
    double largest = 1;
    for (int i = 0; i < S::n_v; ++i) largest = std::max(largest, std::abs(f[S::n_q + i]));
    for (int i = 0; i < S::n_v; ++i) CHECK(std::abs(vdot[i] - f[S::n_q + i]) <= 1e-12 * largest);
  }
}

}  // namespace

TEST_CASE("the articulated-body factor and the LTDL factor give the passes the same derivatives") {
  std::mt19937 rng(24);
  const auto p7 = models::random_chain_params<7>(rng);
  solves_agree(models::chain<7, models::runtime_axes>(p7), rng);
  const auto p8 = models::random_chain_params<8>(rng);
  solves_agree(models::chain<8, models::planar_axes>(p8), rng);
  auto p4 = models::random_chain_params<4>(rng);
  p4.stiffness = 3;
  p4.damping = 0.4;
  solves_agree(models::chain<4, models::runtime_axes, axis_law::spring_damper>(p4), rng);
  // A free trunk and a leg of two: the ball's rotation nodes, massless
  // translation nodes.
  solves_agree(models::legged<1, 2>(), rng);
  const auto p1 = models::random_chain_params<1>(rng);
  solves_agree(models::chain<1, models::runtime_axes>(p1), rng);
}

TEST_CASE("long chains take the articulated-body factor, and their Jacobian is right") {
  using any16 = decltype(models::chain<16, models::runtime_axes>({}));
  using planar8 = decltype(models::chain<8, models::planar_axes>({}));
  STATIC_REQUIRE_FALSE(detail::articulated_solve<any16>());
  STATIC_REQUIRE_FALSE(detail::articulated_solve<planar8>());
  std::mt19937 rng(2024);
  const auto p24 = models::random_chain_params<24>(rng);
  long_chain_agrees(models::chain<24, models::runtime_axes>(p24), rng);
  const auto p12 = models::random_chain_params<12>(rng);
  long_chain_agrees(models::chain<12, models::planar_axes>(p12), rng);
}

TEST_CASE("a singular mass matrix stops the articulated-body factor with the derivative's reason") {
  // Point masses, the last one on its joint's axis: that joint moves nothing
  // with inertia, and its pivot is zero.
  std::mt19937 rng(7);
  auto p = models::random_chain_params<24>(rng);
  p.d[23] = Vec3d::Zero();
  const auto s = models::chain<24, models::runtime_axes, axis_law::none, gravity_kind::uniform, inertia_kind::point>(p);
  using S = std::remove_cvref_t<decltype(s)>;
  STATIC_REQUIRE(detail::articulated_solve<S>());
  auto x = test::random_state(s, rng);
  typename S::state_type f;
  REQUIRE_THROWS_WITH(s(x, f, 0.0), Catch::Contains("singular mass matrix") && Catch::Contains("\"j23\""));
  REQUIRE_THROWS_WITH(jacobian(s, 0.0, x), Catch::Contains("singular mass matrix") && Catch::Contains("\"j23\""));
}
