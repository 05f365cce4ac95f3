// renamed<Named>(scene) takes a Named that derives from the scene's
// structure and adds nothing; one that adds a member is refused, naming
// what Named must be.
#include <flange/equations_of_motion.hpp>
using namespace flange;
struct arm_scene : decltype(models::robot_arm())::scene_type {
#ifdef FLANGE_KO
  double extra = 0;
#endif
};
int main() {
  const auto arm = renamed<arm_scene>(models::robot_arm());
  std::array<double, 2 * decltype(arm)::n_q> x{}, dx{};
  arm(x, dx, 0.0);
}
