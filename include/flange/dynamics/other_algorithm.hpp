// v̇ by the algorithm accelerations() does not use for a scene
// (algorithm.hpp): Newton–Euler with the mass matrix where the cost model
// picks the articulated body, and the other way round. The two share the
// joints' motions and the scene's constants but none of their passes, so
// their agreement checks both; the tests and the fuzz target hold the
// default against this. A scene with loops has only the first algorithm.
#pragma once
#include "flange/dynamics/algorithm.hpp"

namespace flange {

template <class S, class T>
void accelerations_other(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  static_assert(!detail::has_loops<S>, "flange: a scene with loops has one forward algorithm (dynamics/algorithm.hpp)");
  if constexpr (algorithm_for<S>() == forward_algorithm::articulated_body)
    accelerations_mass_matrix(scene, t, q, v, vdot);
  else
    accelerations_articulated_body(scene, t, q, v, vdot);
}

}  // namespace flange
