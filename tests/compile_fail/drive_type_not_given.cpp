// A Revolute drive given a callable without its type is refused in one
// static_assert that names the fix; the ok half uses revolute<…>(f).
#include <flange/equations_of_motion.hpp>
using namespace flange;
int main() {
  auto tau = [](auto t, const auto& x) { return -x.q(0) - t; };
#ifdef FLANGE_KO
  auto joint = Revolute<"joint", axis::z, axis_law::none, double>({.tau = tau});
#else
  auto joint = revolute<"joint", axis::z>(tau);
#endif
  const double q[1] = {0.5}, v[1] = {0.0};
  double f[1];
  joint.generalized_force(0.0, joint_state<double>{q, v, 1}, q, v, f);
  return f[0] < 0 ? 0 : 1;
}
