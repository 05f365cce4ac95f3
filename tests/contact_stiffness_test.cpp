// A ball thrown onto the ground with contact stiffnesses from 1e3 to 1e8 N/m
// (the linear stiffness at rest under its weight) runs through simulate()
// without failure with dopri5 and with rosenbrock4 (the exact Jacobian), and
// both come to rest at the penetration Hertz's law gives. What each costs is
// benchmarks/contact_steppers (docs/contact.md's table).
#include <catch2/catch.hpp>
#include <flange/flange.hpp>
#include <flange/models/ball.hpp>
#include <flange/simulate/rosenbrock4.hpp>

#include <cmath>

using namespace flange;

namespace {
/// Thrown from 0.3 m, sideways and spinning; 3 s: it bounces, slides, rolls and settles.
template <class Method, class S>
typename S::state_type throw_and_settle(const S& s) {
  typename S::state_type x{0, 0.3, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 0, 5.0};
  return simulate<Method>(s, x, 0.0, 3.0, {.tolerance = 1e-6, .max_rhs_evals = 20'000'000});
}
}  // namespace

TEST_CASE("a ball lands and settles with contact stiffness from 1e3 to 1e8 N/m, with dopri5 and with rosenbrock4") {
  for (double k_lin : {1e3, 1e4, 1e5, 1e6, 1e7, 1e8}) {
    models::ball_params p;
    p.material.stiffness = models::stiffness_for(p, k_lin);
    const auto s = models::ball_on_ground(p);
    const double rest = p.radius - models::rest_depth(p);
    // The stiffness at rest is the one asked for: (3/2)·m·g/δ.
    CHECK(std::abs(1.5 * p.m * 9.81 / models::rest_depth(p) - k_lin) < 1e-9 * k_lin);
    const auto a = throw_and_settle<method::dopri5>(s);
    const auto b = throw_and_settle<method::rosenbrock4>(s);
    INFO("k = " << k_lin << " N/m: at rest " << rest << " m; dopri5 " << a[1] << " m, rosenbrock4 " << b[1] << " m");
    // Settled on the ground (the bounces die within 3 s at c = 0.5 s/m; it
    // rolls on), at Hertz's depth: the height to the tolerance's order,
    // relative to the depth.
    CHECK(std::abs(a[1] - rest) < 1e-3 * models::rest_depth(p) + 1e-6);
    CHECK(std::abs(b[1] - rest) < 1e-3 * models::rest_depth(p) + 1e-6);
  }
}
