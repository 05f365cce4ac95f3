// The four-bar with run-time axes is a spatial loop: its cut revolute locks
// 5 relative motions, and the tree has 3 rates. With axis::z on every joint
// the loop is planar (2 constraints) and compiles.
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
#ifdef FLANGE_KO
  auto s = models::fourbar<axis::any>({});
#else
  auto s = models::fourbar<axis::z>({});
#endif
  std::array<double, 6> x{}, dx{};
  s(x, dx, 0.0);
}
