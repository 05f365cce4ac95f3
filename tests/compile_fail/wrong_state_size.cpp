// A state whose type fixes a size other than the scene's n_state = 2·n_q is
// refused at compile time (a std::vector of the wrong size throws instead).
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
  const auto arm = models::robot_arm();
#ifdef FLANGE_KO
  std::array<double, 3> x{}, dx{};
#else
  std::array<double, 2> x{}, dx{};
#endif
  arm(x, dx, 0.0);
}
