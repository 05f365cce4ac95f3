// The articulated body's blocks (dynamics/articulated_body.hpp, the step
// objects' block<R>; schedule.hpp, the plan): in a large scene, links in a row of one kind run their
// steps up and down as one, each step handing the next its articulated
// inertia, bias force or acceleration in registers (planar scenes; a
// spatial link's steps run alone, costs.hpp). Chains of 13 links computed in
// the shared form (planar: in blocks), unrolled and by Newton–Euler + M,
// which shares none of the passes; a singular pivot inside a block,
// reported at its own joint; and the step down's two forms (costs.hpp,
// aba_down_early): early on a chain, late on the legged tree.
#include <catch2/catch.hpp>
#include <flange/dynamics/forward_dynamics.hpp>
#include <flange/equations_of_motion.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/legged.hpp>

#include "aba_agreement.hpp"
#include "random_params.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

using namespace flange;

namespace {

constexpr int N = 13;

/// The plan of the shared form for scene S (dynamics/schedule.hpp).
template <class S>
using shared_plan = detail::aba_plan<algebra_t<S>, S, aba_steps::shared, detail::aba_kinds<algebra_t<S>, S, double>>;
/// The longest block the shared form runs for scene S (costs.hpp).
template <class S>
constexpr int block_links = algebra_t<S>::planar ? detail::aba_block_links.planar : detail::aba_block_links.spatial;

/// The block lengths the shared form runs for scene S.
template <class S>
std::vector<int> block_lengths() {
  constexpr auto units = shared_plan<S>::units;
  std::vector<int> r;
  for (int u = 0; u < units.n; ++u) r.push_back(units.len[u]);
  return r;
}

// Round-off of either algorithm, amplified by the mass matrix's condition.
constexpr double round_off = test::aba_round_off;

template <template <int> class Axes>
void check_chain(const char* what) {
  std::mt19937 rng(3);
  const auto c = models::chain<N, Axes>(test::chain_params<N>(rng));
  using S = std::remove_cvref_t<decltype(c)>;
  // Links 2 … 13 are of one kind (link 1 hangs on the World): the shared
  // form runs them in blocks of the longest length (planar: 8 and 4).
  const auto lengths = block_lengths<S>();
  INFO(what);
  REQUIRE(lengths.size() >= 2);
  CHECK(*std::max_element(lengths.begin(), lengths.end()) == block_links<S>);
  CHECK(std::accumulate(lengths.begin(), lengths.end(), 0) == N);
  const double w = test::worst_aba_disagreement(c, 11, 30);
  INFO("worst |Δv̇| / max|v̇| = " << w);
  CHECK(w < round_off);
}

}  // namespace

TEST_CASE("chains computed in blocks (and shared steps) agree with the unrolled steps and with Newton–Euler + M") {
  check_chain<models::planar_axes>("planar chain");
  check_chain<models::runtime_axes>("spatial chain, run-time axes");
}

TEST_CASE("a massless last link inside a block is a singular pivot at its own joint") {
  std::mt19937 rng(3);
  auto p = test::chain_params<N>(rng);
  p.m[N - 1] = 0;
  p.J[N - 1].setZero();
  const auto c = models::chain<N, models::planar_axes>(p);
  using S = std::remove_cvref_t<decltype(c)>;
  REQUIRE(block_lengths<S>().back() > 1);  // the last link is not alone
  std::array<double, S::n_q> q{};
  std::array<double, S::n_v> v{}, vd{};
  for (int i = 0; i < S::n_q; ++i) q[i] = 0.1 * i;
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(accelerations_articulated_body<aba_steps::shared>(c, 0.0, q.data(), v.data(), vd.data()),
                    Contains("singular mass matrix") && Contains("joint \"j12\" (v[12])"));
  CHECK_THROWS_WITH(accelerations_articulated_body<aba_steps::unrolled>(c, 0.0, q.data(), v.data(), vd.data()),
                    Contains("singular mass matrix") && Contains("joint \"j12\" (v[12])"));
}

TEST_CASE("the step down is early on a chain and late on a branched tree, and both agree with Newton–Euler + M") {
  std::mt19937 rng(3);
  const auto c = models::chain<N, models::runtime_axes>(test::chain_params<N>(rng));
  const auto t = models::legged<4, 4>();
  using C = std::remove_cvref_t<decltype(c)>;
  using L = std::remove_cvref_t<decltype(t)>;
  STATIC_REQUIRE(shared_plan<C>::early);
  // 17 links (the trunk and four legs of four), the deepest 5 deep.
  STATIC_REQUIRE(detail::tree_depth<L>() == 5);
  STATIC_REQUIRE(!shared_plan<L>::early);
  // The base's quaternion (q[3 … 6]) must be a unit one.
  const double worst = test::worst_aba_disagreement(t, 11, 20, [](auto& q) {
    double n2 = 0;
    for (int i = 3; i < 7; ++i) n2 += q[i] * q[i];
    for (int i = 3; i < 7; ++i) q[i] /= std::sqrt(n2);
  });
  INFO("worst |Δv̇| / max|v̇| = " << worst);
  CHECK(worst < round_off);
}
