// Which forward-dynamics algorithm a scene's type calls for, chosen at compile
// time from a cost model, and v̇ by it.
//
// flange has two: Newton–Euler for the bias, the composite-rigid-body mass
// matrix and an unrolled LDLᵀ (forward_dynamics.hpp), and Featherstone's
// articulated-body algorithm (articulated_body.hpp). The first is cheapest on
// small scenes, but its mass matrix carries every column up through every
// ancestor and its LDLᵀ is dense, so on a chain of N links its work grows like
// N² and N³ (and so does its unrolled code, and the compiler's time). The
// second does a fixed amount of work per link. The model estimates both in
// nanoseconds from the tree's shape (measured constants, docs/performance.md
// "Choosing the algorithm"):
//
//   newton_euler_mass_matrix ≈ Σ_links nv·(a + b·(rates of its ancestors))
//   articulated_body         ≈ Σ_links (c + d·(nv − 1)²)
//
// with one set of constants for the spatial algebra and one for the planar,
// and b and c larger for a link turned by a general rotation than by a
// typed one (a coordinate rotation, or the product of two that a link in its
// joint's axis frame turns by: axis_frames.hpp). The crossovers this gives on
// chains, and how they were measured (tools/chain_counts.sh), are in
// docs/performance.md, "Choosing the algorithm".
// A scene with loops always takes the first: its constraint solve needs M.
#pragma once
#include "flange/detail/inline.hpp"
#include "flange/dynamics/articulated_body.hpp"
#include "flange/dynamics/costs.hpp"
#include "flange/dynamics/forward_dynamics.hpp"

namespace flange {

enum class forward_algorithm { newton_euler_mass_matrix, articulated_body };

namespace detail {

/// The two estimates for scene S, ns: {Newton–Euler + mass matrix, articulated body}.
template <class S>
constexpr std::pair<double, double> algorithm_estimates() {
  constexpr auto k = costs_for<algebra_t<S>>();
  constexpr auto& tree = S::tree;
  constexpr auto general = []<int... L>(std::integer_sequence<int, L...>) {
    return std::array<bool, sizeof...(L) + 1>{false, general_rotation<S, L + 1>()...};
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  double ne = 0, aba = 0;
  for (int L = 1; L < tree.n_links; ++L) {
    const int nv = S::table.nv[tree.link_joint[L]];
    int above = 0;  // rates of the link's ancestors: the entries its columns are carried through
    for (int P = tree.link_parent[L]; P > 0; P = tree.link_parent[P]) above += S::table.nv[tree.link_joint[P]];
    ne += k.ne_rate * nv + (general[L] ? k.carry_general : k.carry_typed) * nv * above;
    aba += (general[L] ? k.aba_general : k.aba_typed) + k.aba_dof * (nv - 1) * (nv - 1);
  }
  return {ne, aba};
}

}  // namespace detail

/// The algorithm accelerations() uses for scene S.
template <class S>
constexpr forward_algorithm algorithm_for() {
  if constexpr (detail::has_loops<S>) {
    return forward_algorithm::newton_euler_mass_matrix;
  } else {
    constexpr auto e = detail::algorithm_estimates<S>();
    return e.second < e.first ? forward_algorithm::articulated_body : forward_algorithm::newton_euler_mass_matrix;
  }
}

namespace detail {
/// Whether the derivative is compiled into its caller rather than called:
/// for a scene of one rate (the model's estimate at most 20 ns). Called, the
/// derivative writes ẋ element by element and a stepper's vectorised stage
/// sums read the two elements of such a state at once, which the processor
/// cannot forward from two stores: each stage waits for them to retire.
/// Larger scenes gain nothing or lose (docs/performance.md, "Why the hot
/// path is written as it is"): there a call stays, and a stepper's stages
/// share one copy of the derivative.
template <class S>
constexpr bool inline_derivative() {
  return algorithm_for<S>() == forward_algorithm::newton_euler_mass_matrix && algorithm_estimates<S>().first <= 20;
}
}  // namespace detail

/// v̇ at (t, q, v) by the algorithm the scene's type calls for (algorithm_for).
/// Throws simulation_error if the mass matrix (or an articulated inertia) is singular.
template <class S, class T>
FLANGE_INLINE void accelerations(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  if constexpr (algorithm_for<S>() == forward_algorithm::articulated_body)
    accelerations_articulated_body(scene, t, q, v, vdot);
  else if constexpr (detail::inline_derivative<S>())
    detail::accelerations_inline<algebra_t<S>>(scene, t, q, v, vdot);
  else
    accelerations_mass_matrix(scene, t, q, v, vdot);
}

}  // namespace flange
