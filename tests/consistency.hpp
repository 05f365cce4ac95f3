// Consistency along a trajectory: every frame's R orthogonal, the residual of
// the components' equations ≈ 0, and the second algorithm agreeing.
#pragma once
#include <algorithm>

#include <flange/dynamics/other_algorithm.hpp>
#include <flange/dynamics/recover.hpp>

namespace flange::test {

struct consistency {
  double orthogonality = 0;  ///< max |R·R' − 1| over frames and samples
  double residual = 0;       ///< max scaled residual
  double algorithms = 0;     ///< max |q̈_NE − q̈_ABA| / (1 + |q̈|)
  int samples = 0;

  template <class S, class X>
  void sample(const S& scene, double t, const X& x) {
    const auto sol = recover(scene, t, x);
    for (const auto& f : sol.frames)
      orthogonality = std::max(orthogonality, (f.R * f.R.transpose() - Mat3d::Identity()).cwiseAbs().maxCoeff());
    residual = std::max(residual, scaled_residual(scene, sol));
    std::array<double, S::n_v> aba;
    accelerations_other(scene, t, sol.q.data(), sol.v.data(), aba.data());
    for (int i = 0; i < S::n_v; ++i)
      algorithms = std::max(algorithms, std::abs(aba[i] - sol.vdot[i]) / (1 + std::abs(sol.vdot[i])));
    ++samples;
  }
};

}  // namespace flange::test
