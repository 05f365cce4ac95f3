// Integration methods by name, for simulate<Method>(…) and the ensembles
// (ensemble::make_with<Method>): each makes the stepping adapter
// (stepping.hpp) the integration loop drives, for a scene and a state type,
// at an absolute and a relative tolerance.
//
//   method::dopri5          Dormand–Prince 5(4) with dense output (the default):
//                           Odeint's make_dense_output(…, runge_kutta_dopri5)
//   method::bulirsch_stoer  Bulirsch–Stoer with dense output: high order for smooth
//                           scenes at tight tolerances (Odeint's implementation
//                           allocates two small vectors per step); its header,
//                           bulirsch_stoer.hpp, brings Boost.Math's special
//                           functions, so flange.hpp leaves it out
//   method::rosenbrock4     the stiff stepper with the exact Jacobian (rosenbrock4.hpp)
//
// A method of one's own is a type with make<X>(abs_tol, rel_tol) returning
// an Odeint dense-output stepper, or with stepping<X>(scene, abs_tol,
// rel_tol) returning an adapter.
#pragma once
#include <boost/numeric/odeint/stepper/generation.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>

#include "flange/simulate/stepping.hpp"

namespace flange {

namespace method {
/// Dormand–Prince 5(4) with dense output.
struct dopri5 {
  template <class X>
  static auto make(double abs_tol, double rel_tol) {
    namespace odeint = boost::numeric::odeint;
    return odeint::make_dense_output(abs_tol, rel_tol, odeint::runge_kutta_dopri5<X>());
  }
};
/// Bulirsch–Stoer with dense output: <flange/simulate/bulirsch_stoer.hpp>.
struct bulirsch_stoer;
}  // namespace method

namespace detail {
template <class T>
concept complete_type = requires { sizeof(T); };
/// Refuses a method whose header is not included, in one error; true when
/// the method can be used.
template <class Method>
constexpr bool method_available() {
  static_assert(complete_type<Method>,
                "flange: this method is declared but its header is not included: "
                "method::bulirsch_stoer needs #include <flange/simulate/bulirsch_stoer.hpp>");
  return complete_type<Method>;
}
/// The stepping adapter of a method for the scene S and the state X (a
/// complete method: method_available).
template <class Method, class X, class S>
auto method_stepping(const S& scene, double abs_tol, double rel_tol) {
  if constexpr (requires { Method::template stepping<X>(scene, abs_tol, rel_tol); }) {
    return Method::template stepping<X>(scene, abs_tol, rel_tol);
  } else {
    (void)scene;
    using Stepper = decltype(Method::template make<X>(abs_tol, rel_tol));
    return dense_stepping<Stepper, X>(Method::template make<X>(abs_tol, rel_tol));
  }
}
}  // namespace detail

}  // namespace flange
