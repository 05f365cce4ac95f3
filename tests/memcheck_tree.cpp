// Run under valgrind's memcheck by ctest (when valgrind is installed): the
// derivative, the articulated-body algorithm, recovery with the residual, and
// one integration of a branched tree with every joint and force element.
// Every result is tested for finiteness, so a value computed from memory the
// algorithms never wrote reaches a branch, where memcheck reports it as an
// uninitialised read (and ctest fails on --error-exitcode).
#include <cstdio>

#include <flange/dynamics/other_algorithm.hpp>
#include <flange/simulate/odeint.hpp>

#include "random_params.hpp"

using namespace flange;

int main() {
  constexpr auto shape = models::random_tree_shape(3, 8, false);
  constexpr auto planar_shape = models::random_tree_shape(5, 7, true);
  std::mt19937 rng(3);
  const auto tree = models::tree<shape>(test::tree_params<shape.n>(rng));
  const auto planar = models::tree<planar_shape>(test::tree_params<planar_shape.n>(rng));
  int bad = 0;
  auto check = [&](const char* what, double v) {
    if (!std::isfinite(v)) {
      std::printf("%s is not finite\n", what);
      ++bad;
    }
  };
  auto exercise = [&](const auto& s) {
    using S = std::remove_cvref_t<decltype(s)>;
    typename S::state_type x, dx;
    for (auto& v : x) v = test::uniform(rng, -1, 1);
    s(x, dx, 0.1);
    for (double v : dx) check("the derivative", v);
    std::array<double, S::n_q> aba;
    accelerations_other(s, 0.1, x.data(), x.data() + S::n_q, aba.data());
    for (double v : aba) check("the articulated-body accelerations", v);
    const auto sol = recover(s, 0.1, x);
    check("the recovered energy", sol.energy());
    check("the residual", scaled_residual(s, sol));
    odeint::integrate_adaptive(odeint::make_controlled(1e-8, 1e-8, odeint::runge_kutta_dopri5<typename S::state_type>()),
                               s, x, 0.0, 0.2, 1e-3);
    for (double v : x) check("the integrated state", v);
  };
  exercise(tree);
  exercise(planar);
  std::printf("memcheck_tree: %s\n", bad ? "non-finite results" : "ok");
  return bad ? 1 : 0;
}
