// An input written for double cannot carry dual numbers: asking for the
// Jacobian must say so, not silently treat the input as constant.
#include <flange/equations_of_motion.hpp>
#include <flange/simulate/jacobian.hpp>
using namespace flange;
int main() {
#ifdef FLANGE_KO
  auto push = [](double t) { return std::sin(t); };
#else
  auto push = [](auto t) {
    using std::sin;
    return sin(t);
  };
#endif
  const auto crane = models::gantry_crane({}, push);
  const auto J = jacobian(crane, 0.0, std::array<double, 4>{});
  return J(0, 0) > 1;
}
