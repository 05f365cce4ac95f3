// The scale benchmark's large cases (scale.hpp): chains of 32 and 64 links
// and the floating tree of 64 joints. Each is its own function so that
// scale.cpp can run them in their scenes' order; they are built only with
// -DFLANGE_SCALE_FULL=ON (benchmarks/CMakeLists.txt): each 64-link scene
// costs the compiler one to two minutes and 2–4 GB, too much for every CI
// build. KIND picks the unit's scene (one unit per kind, built in parallel).
#include "scale.hpp"

namespace scale {
#if FLANGE_SCALE_KIND == 0
void planar_chains_large() { large_chains<z_axes>("chain_planar"); }
#elif FLANGE_SCALE_KIND == 1
void spatial_chains_large() { large_chains<flange::models::runtime_axes>("chain_spatial"); }
#elif FLANGE_SCALE_KIND == 2
void spatial_typed_chains_large() { large_chains<xyz_axes>("chain_spatial_typed"); }
#else
void trees_large() { tree_case<16>("tree_legged"); }
#endif
}  // namespace scale
