// The scale benchmark's harness (benchmarks/scale/): one flange scene and the
// same mechanism in MuJoCo, both at the same random state. It checks that
// MuJoCo's q̈ (mj_forward) equals flange's to 1e-9 relative, then times both
// in the same run, alternating in rounds, and prints one line:
//
//   scale <scene> N=<n> flange_ns=<x> mujoco_ns=<y> ratio=<y/x>
//
// x and y are the medians over the rounds of the time per call: flange's
// whole derivative (q̇ and v̇ by the algorithm the scene's type picks,
// dynamics/forward_dynamics.hpp) and MuJoCo's mj_forward with contacts and
// constraints off. Rows are kept for the exponent fits scale.cpp prints.
#pragma once
#include <flange/flange.hpp>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "../peers/mujoco_models.hpp"
#include "../rounds.hpp"

namespace scale {

// The cases, one translation unit per kind (chains_*.cpp, tree.cpp; the
// large ones in large.cpp), run by scale.cpp.
void planar_chains();
void spatial_chains();
void spatial_typed_chains();
void trees();
void planar_chains_large();
void spatial_chains_large();
void spatial_typed_chains_large();
void trees_large();

struct row {
  std::string scene;
  int n;
  double flange_ns, mujoco_ns;
};
inline std::vector<row>& rows() {
  static std::vector<row> r;
  return r;
}

using rounds::block_ns;
using rounds::calls_for;
using rounds::median;

/// Compares and times a scene (flange state x) against the MuJoCo model xml.
template <class Scene>
void compare(const std::string& name, int n, const Scene& scene, const typename Scene::state_type& x,
             const std::string& xml) {
  mjModel* m = peer::load(xml);
  if (!m) std::exit(1);
  mjData* d = mj_makeData(m);
  std::vector<double> xv(x.begin(), x.end());
  peer::to_mujoco(m, xv, d);
  mj_forward(m, d);
  typename Scene::state_type dx{};
  scene(x, dx, 0.0);
  double err = 0, big = 1;
  for (int i = 0; i < m->nv; ++i) {
    err = std::max(err, std::abs(d->qacc[i] - dx[Scene::n_q + i]));
    big = std::max(big, std::abs(d->qacc[i]));
  }
  if (!(err <= 1e-9 * big)) {
    std::printf("scale %s N=%d: MuJoCo's q̈ differs from flange's by %.3g (of %.3g): not the same model\n",
                name.c_str(), n, err, big);
    std::exit(1);
  }
  auto f = [&] {
    asm volatile("" : : "r"(x.data()) : "memory");
    scene(x, dx, 0.0);
    asm volatile("" : : "r"(dx.data()) : "memory");
  };
  auto g = [&] { mj_forward(m, d); };
  const long nf = calls_for(f), ng = calls_for(g);
  std::vector<double> tf, tg;
  for (int r = 0; r < 15; ++r) {
    tf.push_back(block_ns(f, nf));
    tg.push_back(block_ns(g, ng));
  }
  const double xf = median(tf), yg = median(tg);
  std::printf("scale %s N=%d flange_ns=%.1f mujoco_ns=%.1f ratio=%.2f\n", name.c_str(), n, xf, yg, yg / xf);
  std::fflush(stdout);
  rows().push_back({name, n, xf, yg});
  mj_deleteData(d);
  mj_deleteModel(m);
}

/// Axis types: every joint about z (a planar chain), about x, y, z in turn
/// (spatial, typed), or run-time axes (spatial).
template <int>
struct z_axes {
  using type = flange::axis::z;
};
template <int I>
struct xyz_axes {
  using type = flange::axis::coordinate<I % 3>;
};

/// The N-link chain of models/chain.hpp with random parameters and state
/// (the same generator as step_cost's chains).
template <int N, template <int> class Axes>
void chain_case(const std::string& name) {
  using namespace flange;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> s(-1, 1);
  const auto p = models::random_chain_params<N>(rng);
  std::vector<std::array<double, 3>> axis(N), d(N), J(N);
  std::vector<double> m(N);
  for (int i = 0; i < N; ++i) {
    d[i] = {p.d[i](0), p.d[i](1), p.d[i](2)};
    m[i] = p.m[i];
    J[i] = {p.J[i](0, 0), p.J[i](1, 1), p.J[i](2, 2)};
  }
  [&]<int... I>(std::integer_sequence<int, I...>) {
    ((axis[I] = [&] {
       using A = typename Axes<I>::type;
       if constexpr (A::fixed) return std::array<double, 3>{A::index == 0 ? 1.0 : 0.0, A::index == 1 ? 1.0 : 0.0,
                                                            A::index == 2 ? 1.0 : 0.0};
       else return std::array<double, 3>{p.axis[I](0), p.axis[I](1), p.axis[I](2)};
     }()),
     ...);
  }(std::make_integer_sequence<int, N>{});
  const auto c = models::chain<N, Axes>(p);
  typename std::remove_cvref_t<decltype(c)>::state_type x;
  for (auto& v : x) v = s(rng);
  compare(name, N, c, x, peer::chain_xml(axis, d, m, J, {p.g(0), p.g(1), p.g(2)}));
}

/// The chains of N = 1 … 16 links, and of 32 and 64 (the large build).
template <template <int> class Axes>
void small_chains(const std::string& name) {
  chain_case<1, Axes>(name);
  chain_case<2, Axes>(name);
  chain_case<4, Axes>(name);
  chain_case<8, Axes>(name);
  chain_case<16, Axes>(name);
}
template <template <int> class Axes>
void large_chains(const std::string& name) {
  chain_case<32, Axes>(name);
  chain_case<64, Axes>(name);
}

/// models::legged<4, Links>: a floating trunk and four legs, N = 4·Links
/// joints below the free joint, at a random state (a unit quaternion).
template <int Links>
void tree_case(const std::string& name) {
  using namespace flange;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> s(-1, 1);
  const auto t = models::legged<4, Links>();
  using S = std::remove_cvref_t<decltype(t)>;
  typename S::state_type x;
  for (auto& v : x) v = s(rng);
  double nq = 0;
  for (int i = 3; i < 7; ++i) nq += x[i] * x[i];
  for (int i = 3; i < 7; ++i) x[i] /= std::sqrt(nq);
  compare(name, 4 * Links, t, x, peer::legged_xml(4, Links));
}

}  // namespace scale
