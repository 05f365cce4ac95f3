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
#include <array>
#include <type_traits>

#include "flange/detail/lazy.hpp"
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
/// The default method's stepper for the state X.
template <class X>
using dopri5_stepper = decltype(method::dopri5::make<X>(0.0, 0.0));

/// Whether a checked run (simulate, the ensembles) steps Method through a
/// type-erased system (system_ref, stepping.hpp): the default method does
/// where FLANGE_SHARED_STEPS is defined (flange_precompile_headers defines
/// it, the same in every unit of a program), so that its steps depend on
/// the state type alone and, for the states of small scenes (below), are
/// compiled once per target (FLANGE_COMMON) instead of in every unit that
/// simulates a scene. It is the edit–compile loop's trade: a small scene's
/// unit compiles about 0.5 s faster, and each derivative evaluation of a
/// run is an indirect call (docs/performance.md, "Compile time").
#if defined(FLANGE_SHARED_STEPS)
inline constexpr bool shared_steps_defined = true;
#else
inline constexpr bool shared_steps_defined = false;
#endif
template <class Method>
inline constexpr bool shared_steps = shared_steps_defined && std::is_same_v<Method, method::dopri5>;

#if defined(FLANGE_SHARED_STEPS)
// The default method's step for states of 1 to 16 numbers.
#define FLANGE_DOPRI5_STEP(N)                                                                     \
  FLANGE_COMMON(void dense_step_shared<dopri5_stepper<std::array<double, N>>, std::array<double, N>>( \
      dopri5_stepper<std::array<double, N>>&, system_ref<std::array<double, N>>&, double, double))
FLANGE_DOPRI5_STEP(1)
FLANGE_DOPRI5_STEP(2)
FLANGE_DOPRI5_STEP(3)
FLANGE_DOPRI5_STEP(4)
FLANGE_DOPRI5_STEP(5)
FLANGE_DOPRI5_STEP(6)
FLANGE_DOPRI5_STEP(7)
FLANGE_DOPRI5_STEP(8)
FLANGE_DOPRI5_STEP(9)
FLANGE_DOPRI5_STEP(10)
FLANGE_DOPRI5_STEP(11)
FLANGE_DOPRI5_STEP(12)
FLANGE_DOPRI5_STEP(13)
FLANGE_DOPRI5_STEP(14)
FLANGE_DOPRI5_STEP(15)
FLANGE_DOPRI5_STEP(16)
#undef FLANGE_DOPRI5_STEP
#endif

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
