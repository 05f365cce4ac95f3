// A driven joint written last in a loop would be cut, and its drive would
// act on a coordinate the state does not have: refused, naming the joint.
#include <flange/equations_of_motion.hpp>
using namespace flange;
using models::bar;
int main() {
  auto s = scene(World<"world">{}, Revolute<"crank_pivot", axis::z>{}, bar<"crank">(0.3, 1.0),
                 Revolute<"crank_pin", axis::z>{}, bar<"coupler">(1.0, 2.0), Revolute<"rocker_pin", axis::z>{},
                 bar<"rocker">(0.8, 1.5), FixedTranslation<"ground">({.d = {1, 0, 0}}),
#ifdef FLANGE_KO
                 revolute<"motor", axis::z>(1.0),
#else
                 Revolute<"motor", axis::z>{},
#endif
                 connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
                 connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
                 connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
                 connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "motor.frame_a">,
                 connect<"rocker.frame_b", "motor.frame_b">);
  std::array<double, 6> x{}, dx{};
  s(x, dx, 0.0);
}
