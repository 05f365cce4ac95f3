// initial_state<...> naming one joint twice is refused at compile time.
#include <flange/equations_of_motion.hpp>
#include <flange/models/paper.hpp>
using namespace flange;
int main() {
  const auto crane = models::gantry_crane();
#ifdef FLANGE_KO
  const auto x = initial_state<"pivot", "pivot">(crane, {.q = 0.1}, {.q = 0.2});
#else
  const auto x = initial_state<"pivot", "rail">(crane, {.q = 0.1}, {.q = 0.2});
#endif
  return x[0] > 0;
}
