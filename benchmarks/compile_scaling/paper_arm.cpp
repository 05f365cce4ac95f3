// Compile-time probe: the paper's robot arm (models/paper.hpp), simulated
// with the default method and its cut torque recovered at the end.
#include <cstdio>

#include <flange/flange.hpp>
using namespace flange;

int main() {
  const auto arm = models::robot_arm();
  const auto x = simulate(arm, {-1.57, 0.0}, 0.0, 3.0, {.tolerance = 1e-10});
  std::printf("%.12f %.12f\n", x[0], recover(arm, 3.0, x).cut_at("rod.frame_a").n.z());
}
