// The Jacobian's cost against one derivative of the same scene (docs/performance.md,
// "The Jacobian"):
//
//   build/benchmarks/jacobian
//
// One line per scene (jacobian.hpp), in one process, derivative and Jacobian
// timed in turns, medians of 15 rounds:
//
//   jacobian <scene> N=<n> derivative_ns=<x> jacobian_ns=<y> ratio=<y/x> [dual_ns=<z>] path=<analytic|dual>
//
// path says which jacobian() took: the analytic derivatives
// (dynamics/derivatives.hpp) or dual numbers. dual_ns, jacobian_dual()'s
// time, is there for the named scenes and, with -DFLANGE_SCALE_FULL=ON, for
// the chains up to 16 joints and three floating-base trees; where it is,
// jacobian() is first checked against it (1e-12 of the largest entry) and the
// program fails if they differ. Scenes: chains.cpp, scenes.cpp, trees.cpp,
// large_trees.cpp.
#include "jacobian.hpp"

int main() {
  jacobian_bench::chains();
  jacobian_bench::named_scenes();
  jacobian_bench::trees();
  jacobian_bench::large_trees();
  return jacobian_bench::failures == 0 ? 0 : 1;
}
