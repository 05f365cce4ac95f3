// The derivative, a recovery's energy and its scaled residual of four scenes
// (a spatial chain, a planar chain, the four-bar's loop, a ball on a free
// joint in contact with the ground or above it) at random states, and a
// short simulate() run of the first three (its states at three times and its
// counts), printed as hexadecimal floats. Built twice: with the algorithms'
// steps forced inline and simulate's steps through the scene itself (as
// users build), and with FLANGE_NO_FORCED_INLINE and FLANGE_SHARED_STEPS
// (simulate's steps through a type-erased system; as the unit tests and
// flange_precompile_headers build); the test inline.same_numbers
// (inline_identity.cmake) requires the two outputs to be equal to the last
// bit, so that the unit tests' numbers are the users'.
#include <cstdio>
#include <random>
#include <vector>

#include <flange/equations_of_motion.hpp>
#include <flange/simulate/simulate.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/ball.hpp>
#include <flange/models/linkages.hpp>

#include "random_params.hpp"

using namespace flange;

namespace {
template <class S>
void print_run(const S& s, std::mt19937& rng) {
  typename S::state_type x;
  for (auto& v : x) v = test::uniform(rng, -1, 1);
  normalize(s, x);
  const auto tr = simulate(s, x, std::vector<double>{0.0, 0.05, 0.2});
  for (const auto& xk : tr.x)
    for (double d : xk) std::printf("%a ", d);
  std::printf("| %ld %ld\n", tr.steps, tr.rhs_evals);
}
template <class S>
void print(const S& s, std::mt19937& rng, bool run = true) {
  if (run) print_run(s, rng);
  for (int k = 0; k < 3; ++k) {
    typename S::state_type x, dx;
    for (auto& v : x) v = test::uniform(rng, -1, 1);
    normalize(s, x);
    s(x, dx, 0.1 * k);
    for (double d : dx) std::printf("%a ", d);
    const auto sol = recover(s, 0.1 * k, x);
    std::printf("| %a %a\n", sol.energy(), scaled_residual(s, sol));
  }
}
}  // namespace

int main() {
  std::mt19937 rng(5);
  print(models::chain<8, models::runtime_axes>(test::chain_params<8>(rng)), rng);
  print(models::chain<5, models::planar_axes>(test::chain_params<5>(rng)), rng);
  print(models::fourbar(models::fourbar_params{}), rng);
  print(models::ball_on_ground(), rng, false);  // a random start may overlap the ground
}
