// An input that reads a joint by a misspelt name is refused at compile time
// with one error whose instantiation line lists the scene's joints.
#include <flange/equations_of_motion.hpp>
#include <flange/models/paper.hpp>
using namespace flange;
int main() {
#ifdef FLANGE_KO
  auto pd = [](auto, const auto& x) { return -2.0 * q<"jiont">(x); };
#else
  auto pd = [](auto, const auto& x) { return -2.0 * q<"joint">(x); };
#endif
  const auto arm = scene(World<"world">({.g = {0, -9.81, 0}}), revolute<"joint", axis::z>(pd),
                         FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1, .J = Mat3d::Identity()}),
                         connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
                         connect<"rod.frame_b", "mass.frame_a">);
  std::array<double, 2> x{0.3, 0}, dx;
  arm(x, dx, 0.0);
  return dx[1] < 0;
}
