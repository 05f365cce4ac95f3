// Builds against an installed flange: the umbrella header and the optional
// rosenbrock4 library.
#include <flange/flange.hpp>
#include <flange/simulate/rosenbrock4.hpp>
int main() {
  auto arm = flange::models::robot_arm();
  std::array<double, 2> x{0.3, 0.0};
  flange::integrate_rosenbrock4(arm, x, 0.0, 1.0, 1e-3, 1e-8, 1e-8);
  return std::isfinite(x[0]) ? 0 : 1;
}
