// The scale benchmark's branched tree (scale.hpp): models::legged<4, L>, a
// floating trunk with four legs of L joints, N = 4·L = 4 … 32 (64: large.cpp).
#include "scale.hpp"

namespace scale {
void trees() {
  tree_case<1>("tree_legged");
  tree_case<2>("tree_legged");
  tree_case<4>("tree_legged");
  tree_case<8>("tree_legged");
}
}  // namespace scale
