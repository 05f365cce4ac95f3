// The derivative, a recovery's energy and its scaled residual of four scenes
// (a spatial chain, a planar chain, the four-bar's loop, a ball on a free
// joint in contact with the ground or above it) at random states, printed as
// hexadecimal floats. Built twice, with the algorithms' steps forced inline
// (as users build) and with FLANGE_NO_FORCED_INLINE (as the unit tests
// build); the test inline.same_numbers (inline_identity.cmake) requires the
// two outputs to be equal to the last bit, so that the unit tests' numbers
// are the users'.
#include <cstdio>
#include <random>

#include <flange/equations_of_motion.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/ball.hpp>
#include <flange/models/linkages.hpp>

#include "random_params.hpp"

using namespace flange;

namespace {
template <class S>
void print(const S& s, std::mt19937& rng) {
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
  print(models::ball_on_ground(), rng);
}
