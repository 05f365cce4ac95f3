// Run under valgrind's memcheck by ctest (when valgrind is installed), as
// memcheck_tree.cpp: the Jacobian on each of its paths, with and without
// ∂f/∂t. Dual numbers are not zeroed when made (math/dual.hpp), so every
// number a pass reads must have been written: the analytic derivatives of a
// branched tree with force elements (their loads in dual numbers) and dual
// numbers through its whole derivative, the implicit path of a four-bar,
// dual numbers through a contact (the ball on the ground) and through the
// paper's arm. Every entry is tested for finiteness, so a value computed
// from memory never written reaches a branch, where memcheck reports it.
#include <cstdio>

#include <flange/models/ball.hpp>
#include <flange/models/linkages.hpp>
#include <flange/models/paper.hpp>
#include <flange/simulate/jacobian.hpp>

#include "random_params.hpp"

using namespace flange;

int main() {
  constexpr auto shape = models::random_tree_shape(4, 4, false);
  std::mt19937 rng(4);
  const auto tree = models::tree<shape>(test::tree_params<shape.n>(rng));
  int bad = 0;
  auto check = [&](const char* scene, const char* what, const auto& m) {
    if (!m.allFinite()) {
      std::printf("%s: %s is not finite\n", scene, what);
      ++bad;
    }
  };
  auto exercise = [&](const char* name, const auto& s, auto x) {
    using S = std::remove_cvref_t<decltype(s)>;
    Eigen::Matrix<double, S::n_state, 1> ft;
    check(name, "jacobian()", jacobian(s, 0.1, x));
    check(name, "jacobian() with ∂f/∂t", jacobian(s, 0.1, x, &ft));
    check(name, "∂f/∂t", ft);
    check(name, "jacobian_dual()", jacobian_dual(s, 0.1, x));
  };
  {
    using S = std::remove_cvref_t<decltype(tree)>;
    typename S::state_type x;
    for (auto& v : x) v = test::uniform(rng, -1, 1);
    exercise("a random tree", tree, x);
  }
  {
    const models::fourbar_params p{};
    const auto fb = models::fourbar(p);
    const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
    std::array<double, 6> x{q[0], q[1], q[2], 3.0, 0, 0};
    close_loops<"crank_pivot">(fb, x);
    exercise("the four-bar", fb, x);
  }
  exercise("the ball on the ground", models::ball_on_ground(),
           std::array<double, 13>{0, 0.099, 0, 0, 0, 0, 1, 0.5, -0.1, 0.2, 1.0, 2.0, -3.0});
  exercise("the paper's arm", models::robot_arm({}, Vec3d(0, 0, 0.3)), std::array<double, 2>{0.3, 0.7});
  std::printf("memcheck_jacobian: %s\n", bad ? "non-finite results" : "ok");
  return bad ? 1 : 0;
}
