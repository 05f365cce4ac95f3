// The scale benchmark's spatial typed chains (scale.hpp), N = 1 … 16; a unit
// of its own so that the kinds build in parallel.
#include "scale.hpp"

void scale::spatial_typed_chains() { small_chains<xyz_axes>("chain_spatial_typed"); }
