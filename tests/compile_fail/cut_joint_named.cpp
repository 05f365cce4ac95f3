// A cut joint (the one that closes a loop) has no coordinates in the state:
// naming it where a state coordinate is meant is one error that says so,
// not "no joint of this name".
#include <flange/equations_of_motion.hpp>
#include <flange/models/linkages.hpp>
using namespace flange;
int main() {
  const auto fb = models::fourbar({});
#ifdef FLANGE_KO
  const auto x = initial_state<"rocker_pivot">(fb, {.q = 0.3});
#else
  const auto x = initial_state<"crank_pivot">(fb, {.q = 0.3});
#endif
  return x[0] > 0 ? 0 : 1;
}
