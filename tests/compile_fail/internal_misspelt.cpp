// A recovered internal read by a misspelt name is refused at compile time,
// naming the component and the variable.
#include <flange/equations_of_motion.hpp>
#include <flange/models/paper.hpp>
using namespace flange;
int main() {
  const auto arm = models::robot_arm();
  const auto sol = recover(arm, 0.0, std::array<double, 2>{0.3, 0.0});
#ifdef FLANGE_KO
  return sol.internal<"joint", "ph">() > 0;
#else
  return sol.internal<"joint", "φ">() > 0;
#endif
}
