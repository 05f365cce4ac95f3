// What a link costs: the measured constants that make flange's compile-time
// choices. g++ 12 -O3, measured with tools/chain_counts.sh; the figures
// behind each are in docs/performance.md, "The cost model's constants".
//
// - algorithm_costs (ns) choose the forward-dynamics algorithm
//   (algorithm.hpp);
// - aba_link_instructions (instructions) choose whether the articulated
//   body's steps are unrolled or shared between links (schedule.hpp);
// - aba_block_links chooses how many links in a row run their shared steps
//   as one (schedule.hpp);
// - batch_angles_from chooses whether the links' cosines and sines are
//   computed in one call (links.hpp).
//
// They are kept together because they are one kind of thing, measured with
// one tool: when the passes change, measure and update them here.
#pragma once

namespace flange::detail {

/// The cost model's constants, ns. Newton–Euler + mass matrix: ne_rate per
/// rate, and carry per mass-matrix entry a column is carried through (a rate
/// times each rate of its ancestors), through a general rotation or a typed
/// one (a coordinate axis); articulated body: per link, by its rotation, plus
/// per_dof·(nv − 1)² for a joint of several rates (its D⁻¹).
struct algorithm_costs {
  double ne_rate, carry_general, carry_typed, aba_general, aba_typed, aba_dof;
};
/// The articulated body's per-link constants are its shared form's (the
/// form long chains run); they put the spatial chains' crossover at 7 links
/// and the planar chains' at 8, where tools/chain_counts.sh measured them.
template <class A>
constexpr algorithm_costs costs_for() {
  if constexpr (A::planar) return {12.8, 3.9, 3.9, 25.5, 25.5, 22};
  else return {17.7, 31.7, 20, 110, 75, 22};
}

/// The articulated body's instructions per link when its steps are unrolled
/// into one function: a link in a plane, a link in space turned by a typed
/// rotation (a coordinate axis), and one turned by a general rotation.
struct aba_link_instructions {
  int planar, typed, general;
};
inline constexpr aba_link_instructions aba_unrolled_link{420, 1000, 1460};

/// Unrolled code beyond this many instructions outgrows the processor's
/// caches of decoded instructions: the time per link rises by half while the
/// instructions per link do not. Larger scenes share the steps
/// (schedule.hpp). The planar and spatial thresholds are where unrolled and
/// shared steps measured equal.
struct aba_shared_threshold {
  int planar, spatial;
};
inline constexpr aba_shared_threshold aba_shared_steps_above{7500, 5000};

/// The most links in a row whose shared steps run as one (schedule.hpp):
/// each step hands the next its result in registers, not through memory,
/// and one call does them all. Planar: 8. Spatial: none (1): a spatial step
/// is about a thousand instructions, and a block of them outgrows the caches
/// the sharing is for.
struct aba_block_length {
  int planar, spatial;
};
inline constexpr aba_block_length aba_block_links{8, 1};

/// The form of the articulated body's step down (articulated_body.hpp):
/// early, v̇ = b − Gᵀ·a_P with b and G formed in the step up, or late,
/// v̇ = D⁻¹·(u − Uᵀ·(X·a_P + c)). Early takes the rotation and D⁻¹ off the
/// chain of accelerations that runs down the tree link after link, and costs
/// a carry of U·D⁻¹ to the parent in the step up. It pays where that chain is
/// long, that is where the tree is mostly one chain (its deepest link at
/// least half its links deep), and always in a plane, where the carry is a
/// few products.
constexpr bool aba_down_early(bool planar, int depth, int links) { return planar || 2 * depth >= links; }

/// The fewest angles whose cosines and sines are computed in one call
/// (links.hpp, math/sincos.hpp) rather than one at a time. One call to the
/// vector functions has the longer latency and the better throughput: for
/// one or two angles a call each is faster, from three one call.
inline constexpr int batch_angles_from = 3;

}  // namespace flange::detail
