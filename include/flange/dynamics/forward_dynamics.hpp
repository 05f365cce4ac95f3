// q̈ from (t, q, q̇): the algorithm a scene's type calls for.
//
// A planar scene (dynamics/planar.hpp: every revolute axis the same
// compile-time coordinate axis, every prismatic axis another one) runs planar
// arithmetic; any other tree runs spatial Newton–Euler plus the mass matrix
// (dynamics/newton_euler.hpp). Both are exact; they agree to round-off
// (tests/planar_test.cpp). Call accelerations_newton_euler directly to force
// the spatial algorithm.
#pragma once
#include "flange/dynamics/newton_euler.hpp"
#include "flange/dynamics/planar.hpp"

namespace flange {

template <class S, class T>
void accelerations(const S& scene, const T& t, const T* q, const T* qd, T* qdd) {
  if constexpr (detail::planar_axis<S>() >= 0) accelerations_planar(scene, t, q, qd, qdd);
  else accelerations_newton_euler(scene, t, q, qd, qdd);
}

}  // namespace flange
