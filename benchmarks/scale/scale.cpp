// flange against MuJoCo as mechanisms grow (docs/performance.md, "Scale").
//
//   build/benchmarks/scale
//
// For each scene and size, the scene's derivative and MuJoCo's mj_forward on
// the same model (checked to give the same q̈ to 1e-9 at a random state),
// timed in the same run: one line per case,
//
//   scale <scene> N=<n> flange_ns=<x> mujoco_ns=<y> ratio=<y/x>
//
// then, per scene, the exponent p of a least-squares fit ns ∝ N^p over
// N = 8 and up:
//
//   fit <scene> N=8..<max> flange_exponent=<p> mujoco_exponent=<p>
//
// The default build has N = 1 … 16 (the tree: 4 … 32); N = 32 and 64 need
//   cmake -S . -B build -DFLANGE_SCALE_FULL=ON && cmake --build build --target scale
#include <cmath>
#include <cstdio>
#include <map>

#include "scale.hpp"

using rounds::exponent;

int main() {
  std::printf("MuJoCo %s\n", mj_versionString());
  // N = 32 and 64 only when built (-DFLANGE_SCALE_FULL=ON)
  scale::planar_chains();
#if FLANGE_SCALE_FULL
  scale::planar_chains_large();
#endif
  scale::spatial_chains();
#if FLANGE_SCALE_FULL
  scale::spatial_chains_large();
#endif
  scale::spatial_typed_chains();
#if FLANGE_SCALE_FULL
  scale::spatial_typed_chains_large();
#endif
  scale::trees();
#if FLANGE_SCALE_FULL
  scale::trees_large();
#endif
  std::map<std::string, std::pair<std::vector<std::pair<double, double>>, std::vector<std::pair<double, double>>>> fits;
  for (const auto& r : scale::rows())
    if (r.n >= 8) {
      fits[r.scene].first.emplace_back(r.n, r.flange_ns);
      fits[r.scene].second.emplace_back(r.n, r.mujoco_ns);
    }
  for (const auto& [scene, f] : fits)
    std::printf("fit %s N=8..%.0f flange_exponent=%.2f mujoco_exponent=%.2f\n", scene.c_str(), f.first.back().first,
                exponent(f.first), exponent(f.second));
}
