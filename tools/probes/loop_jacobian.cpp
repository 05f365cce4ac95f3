// The four-bar of models/linkages.hpp (a loop: the implicit path of
// simulate/jacobian.hpp) at the Jacobian benchmark's state, its jacobian()
// or its derivative called K times, for callgrind's instruction counts.
// Not part of the CMake build:
//
//   g++ -std=c++20 -O3 -DNDEBUG -Iinclude -isystem /usr/include/eigen3 tools/probes/loop_jacobian.cpp -o /tmp/lj
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null /tmp/lj 2000     # jacobian()
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null /tmp/lj 2000 d   # the derivative
//
// An instruction count a call is the difference of two runs' totals (K =
// 2000 and 1000) over 1000, so that start-up does not count.
#include <flange/flange.hpp>
#include <flange/models/linkages.hpp>
#include <flange/simulate/jacobian.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  using namespace flange;
  const models::fourbar_params p{};
  const auto fb = models::fourbar(p);
  using S = std::remove_cvref_t<decltype(fb)>;
  const auto q0 = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
  std::array<double, 6> x{q0[0], q0[1], q0[2], 3.0, 0, 0};
  close_loops<"crank_pivot">(fb, x);
  const long k = argc > 1 ? std::atol(argv[1]) : 1000;
  const bool derivative = argc > 2;
  double sum = 0, step = 1e-12;
  jacobian_matrix<S> J;
  std::array<double, 6> f;
  for (long i = 0; i < k; ++i) {
    if (derivative) {
      fb(x, f, 0.0);
      sum += f[5];
    } else {
      jacobian(fb, 0.0, x, J);
      sum += J(5, 0);
    }
    x[0] += step;  // a new state each call (it stays on the loop to round-off)
    step = -step;
    asm volatile("" : : "r"(x.data()) : "memory");
  }
  std::printf("%.17g\n", sum);
}
