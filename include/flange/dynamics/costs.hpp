// What a link costs: the measured constants that make flange's compile-time
// choices. g++ 12 -O3 on the development machine, measured with
// tools/chain_counts.sh (docs/performance.md, "Choosing the algorithm").
//
// - algorithm_costs (ns) choose the forward-dynamics algorithm
//   (algorithm.hpp);
// - aba_link_instructions (instructions) choose whether the articulated
//   body's steps are unrolled or shared between links (articulated_body.hpp);
// - aba_block_links chooses how many links in a row run their shared steps
//   as one (articulated_body.hpp);
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
/// The spatial articulated body's typed link (75) is its shared form's
/// cost a link on the stop-42 machine (AMD EPYC, 2 cores), after its
/// inertias' known zeros (articulated_body.hpp): 8 → 16 links, 600 → 1225 ns.
/// It puts the chains' crossover at 7 links, where that machine measured it
/// (run-time axes: Newton–Euler 424 | 638 ns at 6 | 7 links, shared
/// articulated body 436 | 512; typed axes: 497 | 609 ns at 7 | 8 against
/// 512 | 600). The earlier machine's was 125, unrolled, crossover 12
/// (docs/performance.md, "Choosing the algorithm"); general rotations
/// (110) were not measured again. The planar articulated body, after its own
/// known zeros, 35 → 31 (crossover 11 links), and after stop 44's early
/// step down (aba_down_early) 31 → 25.5: crossover 8 links, measured between
/// 7 and 8 (Newton–Euler 141 | 166 ns, articulated body 140 | 156; at 9 and
/// 10 links 202 | 270 against 186 | 206; tools/chain_counts.sh N planar
/// default,other).
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
/// caches of decoded instructions: the time per link rose by half while the
/// instructions per link did not. Larger scenes share the steps
/// (articulated_body.hpp). Planar: 7,500 (the stop-42 machine, after the
/// known zeros: unrolled faster at 16 links, 564 | 609 ns, shared at 20,
/// 802 | 779; 5,904 and 8,388 instructions unrolled; the earlier machine's
/// 13,000 had it between 32 and 48).
/// Spatial: 5,000 (the stop-42 machine, typed and run-time axes alike:
/// unrolled faster at 5 links, shared from 6; typed links measured 909 and
/// axis-frame links 1097 instructions a link unrolled). The earlier machine
/// had the spatial crossover at 8–10 links.
struct aba_shared_threshold {
  int planar, spatial;
};
inline constexpr aba_shared_threshold aba_shared_steps_above{7500, 5000};

/// The most links in a row whose shared steps run as one
/// (articulated_body.hpp, aba_blocks): each step hands the next its result
/// in registers, not through memory, and one call does them all. Planar: 8
/// (32 | 64-link chains, ns: 4 links 839 | 1572, 8 links 808 | 1522, 16
/// links 807 | 1557; without blocks 889 | 1913). Spatial: none, 1 (16-link
/// chain, run-time axes: 1070 ns without, 1407 in blocks of 4, 1812 of 8:
/// a spatial step is about a thousand instructions, and a block of them
/// outgrows the caches the sharing is for).
struct aba_block_length {
  int planar, spatial;
};
inline constexpr aba_block_length aba_block_links{8, 1};

/// The form of the articulated body's step down (articulated_body.hpp,
/// aba_link): early, v̇ = b − Gᵀ·a_P with b and G formed in the step up,
/// or late, v̇ = D⁻¹·(u − Uᵀ·(X·a_P + c)). Early takes the rotation and
/// D⁻¹ off the chain of accelerations that runs down the tree link after
/// link, and costs a carry of U·D⁻¹ to the parent in the step up. It pays
/// where that chain is long, that is where the tree is mostly one chain
/// (its deepest link at least half its links deep), and always in a plane,
/// where the carry is a few products. Planar 32-link chain: 998 → 869 ns;
/// spatial chains, early against late: run-time axes 8 | 16 links 545 | 1115
/// against 573 | 1158 ns, typed axes 8 links 516 against 533; the legged
/// tree of 16 joints (four legs, whose chains run side by side) 1331 against
/// 1233 ns (tools/chain_counts.sh N runtime|typed|planar|tree).
constexpr bool aba_down_early(bool planar, int depth, int links) { return planar || 2 * depth >= links; }

/// The fewest angles whose cosines and sines are computed in one call
/// (links.hpp, math/sincos.hpp) rather than one at a time. One call to the
/// vector functions has the longer latency, about 24 ns for 1 to 8 angles
/// where glibc's sincos takes 16 | 18 | 25 | 35 ns for 1 | 2 | 3 | 4 (each
/// call's angles depending on the previous result; stop-43 machine), while
/// its throughput is better from one angle (6.3 against 8.6 ns). The paper's
/// arm (one angle) in one call: its derivative's latency 10 → 31 ns.
inline constexpr int batch_angles_from = 3;

}  // namespace flange::detail
