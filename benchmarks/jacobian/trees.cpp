// The Jacobian benchmark's floating-base tree (jacobian.hpp), the scale
// benchmark's: models::legged<4, L>, a free trunk with four legs of L joints
// (N = 4·L leg joints and the trunk's six rates). It takes dual numbers (a
// FreeMotion joint is not on the analytic path), whose units cost minutes to
// compile: in the -DFLANGE_SCALE_FULL=ON build only.
#include <cmath>

#include "jacobian.hpp"
#ifdef FLANGE_SCALE_FULL
#include <flange/models/legged.hpp>
#endif

namespace {
#ifdef FLANGE_SCALE_FULL
template <int Links>
void legged(const char* name) {
  using namespace flange;
  const auto s = models::legged<4, Links>();
  auto x = neutral_state(s);
  for (int i = 0; i < decltype(s)::n_state; ++i) x[i] += 0.1 * std::sin(1.3 * i + 0.4);
  normalize(s, x);
  jacobian_bench::measure<false>(name, 4 * Links, s, x);
}
#endif
}  // namespace

void jacobian_bench::trees() {
#ifdef FLANGE_SCALE_FULL
  legged<1>("tree_legged");
  legged<2>("tree_legged");
#endif
}
