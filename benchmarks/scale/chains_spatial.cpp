// The scale benchmark's spatial chains (scale.hpp), N = 1 … 16; a unit
// of its own so that the kinds build in parallel.
#include "scale.hpp"

void scale::spatial_chains() { small_chains<flange::models::runtime_axes>("chain_spatial"); }
