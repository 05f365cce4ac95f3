// What a link costs: the measured constants that make flange's compile-time
// choices. g++ 12 -O3 on the development machine, measured with
// tools/chain_counts.sh (docs/performance.md, "Choosing the algorithm").
//
// - algorithm_costs (ns) choose the forward-dynamics algorithm
//   (algorithm.hpp);
// - aba_link_instructions (instructions) choose whether the articulated
//   body's steps are unrolled or shared between links (articulated_body.hpp).
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
template <class A>
constexpr algorithm_costs costs_for() {
  if constexpr (A::planar) return {12.8, 3.9, 3.9, 35, 35, 22};
  else return {17.7, 31.7, 20, 110, 125, 22};
}

/// The articulated body's instructions per link when its steps are unrolled
/// into one function: a link in a plane, a link in space turned by a typed
/// rotation (a coordinate axis), and one turned by a general rotation.
struct aba_link_instructions {
  int planar, typed, general;
};
inline constexpr aba_link_instructions aba_unrolled_link{480, 1090, 1460};

/// Unrolled code beyond this many instructions outgrows the instruction
/// cache (32 KB L1i): the time per link rose by half while the instructions
/// per link did not. Larger scenes share the steps (articulated_body.hpp).
inline constexpr int aba_shared_steps_above = 13000;

}  // namespace flange::detail
