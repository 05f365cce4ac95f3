// A cut joint (the one that closes a loop) has no coordinates in the state:
// naming it where a state coordinate is meant (q_offset) is one error that
// says so, not "no joint of this name". (initial_state, close_loops and
// get_joint take it by name.)
#include <flange/equations_of_motion.hpp>
#include <flange/models/linkages.hpp>
using namespace flange;
int main() {
  const auto fb = models::fourbar({});
  using S = decltype(fb);
#ifdef FLANGE_KO
  constexpr int o = S::q_offset<"rocker_pivot">();
#else
  constexpr int o = S::q_offset<"crank_pivot">();
#endif
  const auto x = initial_state<"crank_pivot">(fb, {.q = 0.3});
  return x[o] > 0 ? 0 : 1;
}
