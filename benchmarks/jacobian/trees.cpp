// The Jacobian benchmark's floating-base trees (jacobian.hpp), the scale
// benchmark's: models::legged<Legs, L>, a free trunk with legs of L joints
// (N = Legs·L leg joints and the trunk's six rates), for N = 1, 2, 4, 8 and
// 16; and the quadruped of docs/contact.md standing on its feet (four
// contacts, a PD law on each of its 12 joints). All take the analytic path
// (a FreeMotion's rotation rates are its link's ω). jacobian_dual(), whose
// units cost minutes to compile, is timed beside it for four legs of one and
// of two joints and the standing quadruped in the -DFLANGE_SCALE_FULL=ON
// build only.
#include <cmath>

#include <flange/models/legged.hpp>

#include "jacobian.hpp"
#include "states.hpp"

namespace {
template <int Legs, int Links, bool WithDual = false>
void legged(const char* name) {
  const auto [s, x] = jacobian_bench::legged_tree<Legs, Links>();
  jacobian_bench::measure<WithDual>(name, Legs * Links, s, x);
}
}  // namespace

void jacobian_bench::trees() {
  legged<1, 1>("tree_legged");
  legged<2, 1>("tree_legged");
  legged<4, 1, full>("tree_legged");
  legged<4, 2, full>("tree_legged");
  legged<4, 4>("tree_legged");
  {
    using namespace flange;
    const auto s = models::legged<4, 3, true>({}, models::crouch_drive{});
    auto x = models::crouched_state(s);
    x[1] -= 0.05;  // the feet 1 cm into the ground
    for (int i = decltype(s)::n_q; i < decltype(s)::n_state; ++i) x[i] = 0.05 * std::sin(1.3 * i + 0.4);
    measure<full>("quadruped_standing", 12, s, x);
  }
}
