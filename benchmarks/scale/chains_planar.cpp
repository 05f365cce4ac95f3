// The scale benchmark's planar chains (scale.hpp), N = 1 … 16; a unit
// of its own so that the kinds build in parallel.
#include "scale.hpp"

void scale::planar_chains() { small_chains<z_axes>("chain_planar"); }
