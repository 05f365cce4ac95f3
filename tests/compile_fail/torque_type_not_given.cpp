// Torque<"m1">({.M_ext = f}) with a callable f, the natural reading of the
// README, is refused in one static_assert that names the fix; the ok half
// uses the factory that deduces the type, and constants work as before.
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
  auto push = [](auto t) { return Eigen::Matrix<decltype(t), 3, 1>(decltype(t)(0), decltype(t)(0), t); };
#ifdef FLANGE_KO
  auto motor = Torque<"m1">({.M_ext = push});
#else
  auto motor = torque<"m1">(push);
#endif
  auto constant = Torque<"m2">({.M_ext = {0, 0, 1.5}});
  return motor.torque(0.5, joint_state<double>{}).z() > 0 && constant.torque(0.0, joint_state<double>{}).z() > 0;
}
