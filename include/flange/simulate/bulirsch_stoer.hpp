// method::bulirsch_stoer, for simulate<method::bulirsch_stoer>(…) and the
// ensembles: Odeint's Bulirsch–Stoer with dense output, high order for
// smooth scenes at tight tolerances.
//
//   #include <flange/simulate/bulirsch_stoer.hpp>
//   auto x = simulate<method::bulirsch_stoer>(scene, x0, 0.0, 10.0, {.tolerance = 1e-12});
//
// Its own header, outside flange.hpp: Odeint's dense output brings Boost.Math's
// special functions (factorials, binomials, gamma), about 0.5 s of compile
// time in every unit that includes it.
#pragma once
#include "flange/detail/odeint_warnings.hpp"
FLANGE_ODEINT_INCLUDES_BEGIN
#include <boost/numeric/odeint/stepper/bulirsch_stoer_dense_out.hpp>
FLANGE_ODEINT_INCLUDES_END

#include "flange/simulate/method.hpp"

namespace flange::method {
/// Bulirsch–Stoer with dense output.
struct bulirsch_stoer {
  template <class X>
  static auto make(double abs_tol, double rel_tol) {
    return boost::numeric::odeint::bulirsch_stoer_dense_out<X>(abs_tol, rel_tol);
  }
};
}  // namespace flange::method
