// The implicit Jacobian of three loop scenes (simulate/jacobian.hpp,
// detail::jacobian_loops) against their derivative: the four-bar and the
// slider-crank of models/linkages.hpp and a row of four parallelogram
// windows (window_row<4>: 18 states, four loops), each closed at a moving
// state. Prints, per scene, the median ns of 15 rounds of 2000 calls of
// each and their ratio. Not part of the CMake build:
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -isystem /usr/include/eigen3 tools/probes/loop_scenes_jacobian.cpp -o /tmp/ls
//   taskset -c 1 /tmp/ls
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>

#include <array>
#include <cstdio>
#include <string>

#include "median_ns.hpp"

namespace {
double sink = 0;

template <class S, class X>
void run(const char* name, const S& s, const X& x0) {
  auto x = x0;
  double step = 1e-12;
  auto moved = [&] {
    x[0] += step;
    step = -step;
    asm volatile("" : : "r"(x.data()) : "memory");
  };
  typename S::state_type f;
  flange::jacobian_matrix<S> J;
  bool implicit = true;
  const double d = median_ns([&] {
    s(x, f, 0.0);
    sink += f[S::n_state - 1];
    moved();
  });
  const double j = median_ns([&] {
    implicit = flange::detail::jacobian_loops(s, 0.0, x, J) && implicit;
    sink += J(S::n_state - 1, 0);
    moved();
  });
  std::printf("%s n_state=%d derivative_ns=%.0f jacobian_ns=%.0f ratio=%.2f implicit=%d\n", name, S::n_state, d, j,
              j / d, int(implicit));
}
}  // namespace

int main() {
  using namespace flange;
  {
    const models::fourbar_params p{};
    const auto fb = models::fourbar(p);
    const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
    std::array<double, 6> x{q[0], q[1], q[2], 3.0, 0, 0};
    close_loops<"crank_pivot">(fb, x);
    run("fourbar", fb, x);
  }
  {
    const auto sc = models::slider_crank(models::slider_crank_params{});
    std::array<double, 6> x{1.0, 0.2, 0.35, 2.0, 0.5, -0.3};
    close_loops<"crank_pivot">(sc, x);
    run("slider_crank", sc, x);
  }
  {
    const auto row = models::window_row<4>(models::window_row_params{});
    using S = std::remove_cvref_t<decltype(row)>;
    typename S::state_type x{};
    for (int i = 0; i <= 4; ++i) {
      const int k = S::q_offset("post_pivot" + std::to_string(i));
      x[k] = 1.2;
      x[S::n_q + k] = 0.7;
    }
    for (int i = 0; i < 4; ++i) {
      const int k = S::q_offset("top_pin" + std::to_string(i));
      x[k] = -1.2;
      x[S::n_q + k] = -0.7;
    }
    close_loops<"post_pivot0">(row, x);
    run("window_row4", row, x);
  }
  if (sink == 0.123) std::printf("\n");
}
