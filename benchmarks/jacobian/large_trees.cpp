// The Jacobian benchmark's large floating-base trees (jacobian.hpp), in a
// unit of their own so that it compiles beside the others: models::legged<4, 8>,
// a free trunk with four legs of eight joints (N = 32 leg joints, 38
// rates), and in the -DFLANGE_SCALE_FULL=ON build legged<8, 8> (N = 64, 70
// rates, 141 states: past Eigen's fixed-size matrices, its Jacobian sized at
// run time, simulate/jacobian.hpp). The same state as trees.cpp's
// (states.hpp).
#include "jacobian.hpp"
#include "states.hpp"

namespace {
template <int Legs, int Links>
void legged() {
  const auto [s, x] = jacobian_bench::legged_tree<Legs, Links>();
  jacobian_bench::measure<false>("tree_legged", Legs * Links, s, x);
}
}  // namespace

void jacobian_bench::large_trees() {
  legged<4, 8>();
#ifdef FLANGE_SCALE_FULL
  legged<8, 8>();
#endif
}
