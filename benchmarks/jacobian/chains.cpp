// The Jacobian benchmark's chains (jacobian.hpp): random chains with run-time
// axes (chain_any), typed axes turning x, y, z in turn (chain_typed) and
// typed z axes (chain_planar), as in the scale benchmark.
#include "jacobian.hpp"
#include "states.hpp"

namespace {
using jacobian_bench::xyz_axes;

template <int N, template <int> class Axes>
void chain(const char* name) {
  const auto [s, x] = jacobian_bench::random_chain<N, Axes>();
#ifdef FLANGE_SCALE_FULL
  constexpr bool with_dual = N <= 16;  // the dual-number Jacobians cost the unit minutes to compile
#else
  constexpr bool with_dual = N == 1;  // one rate: dual numbers' time beside the passes'
#endif
  jacobian_bench::measure<with_dual>(name, N, s, x);
}
}  // namespace

void jacobian_bench::chains() {
  chain<1, flange::models::runtime_axes>("chain_any");
  chain<2, flange::models::runtime_axes>("chain_any");
  chain<4, flange::models::runtime_axes>("chain_any");
  chain<7, flange::models::runtime_axes>("chain_any");
  chain<16, flange::models::runtime_axes>("chain_any");
  chain<32, flange::models::runtime_axes>("chain_any");
#ifdef FLANGE_SCALE_FULL
  chain<64, flange::models::runtime_axes>("chain_any");
#endif
  chain<2, xyz_axes>("chain_typed");
  chain<4, xyz_axes>("chain_typed");
  chain<7, xyz_axes>("chain_typed");
  chain<16, xyz_axes>("chain_typed");
  chain<2, flange::models::planar_axes>("chain_planar");
  chain<4, flange::models::planar_axes>("chain_planar");
  chain<7, flange::models::planar_axes>("chain_planar");
  chain<16, flange::models::planar_axes>("chain_planar");
}
