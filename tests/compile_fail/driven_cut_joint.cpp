// A loop whose joints all have drives: none can be cut (a drive on a cut
// joint would act on a coordinate the state does not have), so the loop is
// refused, naming the joint the writing order would cut. With one undriven
// joint the loop is cut there instead, whatever the order.
#include <flange/equations_of_motion.hpp>
using namespace flange;
using models::bar;
int main() {
  auto s = scene(World<"world">{}, revolute<"crank_pivot", axis::z>(1.0), bar<"crank">(0.3, 1.0),
                 revolute<"crank_pin", axis::z>(0.0), bar<"coupler">(1.0, 2.0),
#ifdef FLANGE_KO
                 revolute<"rocker_pin", axis::z>(0.0),
#else
                 Revolute<"rocker_pin", axis::z>{},
#endif
                 bar<"rocker">(0.8, 1.5), FixedTranslation<"ground">({.d = {1, 0, 0}}),
                 revolute<"motor", axis::z>(1.0),
                 connect<"world.frame_b", "crank_pivot.frame_a">, connect<"crank_pivot.frame_b", "crank.frame_a">,
                 connect<"crank.frame_b", "crank_pin.frame_a">, connect<"crank_pin.frame_b", "coupler.frame_a">,
                 connect<"coupler.frame_b", "rocker_pin.frame_a">, connect<"rocker_pin.frame_b", "rocker.frame_a">,
                 connect<"world.frame_b", "ground.frame_a">, connect<"ground.frame_b", "motor.frame_a">,
                 connect<"rocker.frame_b", "motor.frame_b">);
  std::array<double, 6> x{}, dx{};
  s(x, dx, 0.0);
}
