// Boost.Odeint's rosenbrock4 behind a plain C-style interface.
//
// Why a compiled file in a header-only library: rosenbrock4 works on uBLAS
// vectors, and Boost 1.74's uBLAS (Debian 12) calls std::allocator::construct,
// which C++20 removed. flange needs C++20, so rosenbrock4 lives here, compiled
// as C++17, and flange/simulate/rosenbrock4.hpp calls it through function
// pointers (no virtual call, no std::function).
#include "flange/simulate/rosenbrock4_bridge.h"

#include <boost/numeric/odeint.hpp>

namespace {
namespace odeint = boost::numeric::odeint;
namespace ublas = boost::numeric::ublas;
using vector = ublas::vector<double>;
using matrix = ublas::matrix<double>;

struct stiff_system {
  const flange_stiff_callbacks* cb;
  void operator()(const vector& x, vector& dxdt, double t) const { cb->f(cb->context, &x[0], &dxdt[0], t); }
};
struct jacobian {
  const flange_stiff_callbacks* cb;
  std::vector<double>* scratch;
  void operator()(const vector& x, matrix& J, double t, vector& dfdt) const {
    const int n = cb->n;
    cb->jacobian(cb->context, &x[0], scratch->data(), &dfdt[0], t);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) J(i, k) = (*scratch)[i * n + k];
  }
};
}  // namespace

extern "C" long flange_rosenbrock4_integrate(const flange_stiff_callbacks* cb, double* x, double t0, double t1,
                                             double dt, double abs_tol, double rel_tol, double observe_dt) {
  const int n = cb->n;
  vector state(n);
  for (int i = 0; i < n; ++i) state[i] = x[i];
  std::vector<double> scratch(static_cast<std::size_t>(n) * n);
  auto stepper = odeint::make_dense_output(abs_tol, rel_tol, odeint::rosenbrock4<double>());
  auto observe = [&](const vector& s, double t) {
    if (cb->observe) cb->observe(cb->context, &s[0], t);
  };
  std::size_t steps = 0;
  try {
    if (observe_dt > 0)
      steps = odeint::integrate_const(stepper, std::make_pair(stiff_system{cb}, jacobian{cb, &scratch}), state, t0, t1,
                                      observe_dt, observe);
    else
      steps = odeint::integrate_adaptive(stepper, std::make_pair(stiff_system{cb}, jacobian{cb, &scratch}), state, t0, t1,
                                         dt, observe);
  } catch (...) {
    return -1;  // the C++20 side rethrows what its callbacks stored
  }
  for (int i = 0; i < n; ++i) x[i] = state[i];
  return static_cast<long>(steps);
}
