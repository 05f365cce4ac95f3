// How the integration loop (integrate.hpp) drives a stepper: one accepted
// step at a time toward an end time, the state it reached, and a restart
// from a state the loop moved (a projection onto the loops, a quaternion
// back to unit norm). One adapter for each kind of Odeint stepper:
//
//   fixed_stepping       a simple stepper (runge_kutta4): steps of the given dt,
//                        the last one shortened to end at t1
//   controlled_stepping  a controlled stepper (make_controlled): try_step until
//                        one is accepted, the last one aimed at t1
//   dense_stepping       a dense-output stepper (make_dense_output,
//                        bulirsch_stoer_dense_out): whole steps, the last one
//                        aimed at t1 as odeint::integrate_adaptive aims it, and
//                        the state anywhere inside the last step (at)
//
// rosenbrock4.hpp adds the stiff stepper's adapter. A restart tells the
// stepper that the state changed under it: a first-same-as-last stepper
// (dopri5) evaluates the derivative at the new state instead of reusing the
// one it holds. A step size that collapses (500 rejections in a row, or
// below 64 ulp of the end time) is thrown as step_collapse, which the loop
// reports with the state and the reason.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>

#include <boost/numeric/odeint/integrate/max_step_checker.hpp>
#include "flange/detail/inline.hpp"
#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <boost/numeric/odeint/stepper/stepper_categories.hpp>
#include <boost/numeric/odeint/util/unwrap_reference.hpp>

namespace flange::detail {

/// A step size that collapsed: the time the failing step started at, the
/// last size tried, and how many attempts were rejected.
struct step_collapse {
  double t, h;
  int rejected;
};

/// The attempts a step may have rejected before it collapsed (Odeint's own
/// dense-output steppers give up at the same count).
inline constexpr int max_rejections = 500;

/// Below 64 ulp of the larger end time a step no longer moves t reliably.
inline double tiny_step(double t0, double t1) {
  return 64 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t0), std::abs(t1));
}

/// Whether a step of size dt from t would end past t1 (either direction).
inline bool passes(double t, double dt, double t1) { return dt > 0 ? t + dt > t1 : t + dt < t1; }

/// What the in-place steppers (simple and controlled) hold for the loop:
/// the state and time after the last step, and before it.
template <class State>
class in_place_state {
 public:
  static constexpr bool dense = false;
  const State& state() const { return x_; }
  const State& previous_state() const { return prev_; }
  double time() const { return t_; }
  double previous_time() const { return t_prev_; }

 protected:
  void begin(const State& x, double t, double dt) {
    x_ = x;
    t_ = t;
    dt_ = dt;
  }
  void before_step() {
    prev_ = x_;
    t_prev_ = t_;
  }
  State x_{}, prev_{};
  double t_ = 0, t_prev_ = 0, dt_ = 0;
};

/// A simple stepper: steps of dt, the last one shortened to end at t1.
template <class Stepper, class State>
class fixed_stepping : public in_place_state<State> {
  using base = in_place_state<State>;

 public:
  explicit fixed_stepping(Stepper st) : st_(std::move(st)) {}
  void start(const State& x, double t, double dt, double) { base::begin(x, t, dt); }
  template <class System>
  void step(System& sys, double t1) {
    base::before_step();
    const bool last = passes(this->t_, this->dt_, t1);
    const double h = last ? t1 - this->t_ : this->dt_;
    st_.do_step(std::ref(sys), this->x_, this->t_, h);
    this->t_ = last ? t1 : this->t_ + h;
  }
  void restart(const State& x) { this->x_ = x; }

 private:
  Stepper st_;
};

/// A controlled stepper: each step tried until accepted, the last one aimed at t1.
template <class Stepper, class State>
class controlled_stepping : public in_place_state<State> {
  using base = in_place_state<State>;

 public:
  explicit controlled_stepping(Stepper st) : st_(std::move(st)) {}
  void start(const State& x, double t, double dt, double t1) {
    base::begin(x, t, dt);
    tiny_ = tiny_step(t, t1);
    if constexpr (requires { st_.reset(); }) st_.reset();
  }
  template <class System>
  void step(System& sys, double t1) {
    namespace odeint = boost::numeric::odeint;
    base::before_step();
    if (passes(this->t_, this->dt_, t1)) this->dt_ = t1 - this->t_;
    int rejected = 0;
    while (st_.try_step(std::ref(sys), this->x_, this->t_, this->dt_) == odeint::fail)
      if (++rejected >= max_rejections || std::abs(this->dt_) < tiny_)
        throw step_collapse{this->t_, this->dt_, rejected};
  }
  void restart(const State& x) {
    this->x_ = x;
    if constexpr (requires { st_.reset(); }) st_.reset();  // a derivative held from the last step is stale
  }

 private:
  Stepper st_;
  double tiny_ = 0;
};

/// A system by reference, its type erased: the derivative behind one
/// pointer to a function. A stepper's step for it depends on the state type
/// alone, so it can be compiled once for every scene with that state
/// (method.hpp's shared dopri5 steps) instead of in every unit that
/// integrates a scene; each evaluation costs an indirect call.
template <class State>
struct system_ref {
  const void* system;
  void (*call)(const void*, const State&, State&, double);
  template <class System>
  explicit system_ref(const System& s)
      : system(&s), call([](const void* p, const State& x, State& dxdt, double t) {
          (*static_cast<const System*>(p))(x, dxdt, t);
        }) {}
  void operator()(const State& x, State& dxdt, double t) const { call(system, x, dxdt, t); }
};
/// f(sys), or where Shared f of a system_ref to it: the steps that take it
/// then depend on the state type alone (simulate/method.hpp compiles them once).
template <bool Shared, class State, class System, class F>
FLANGE_INLINE decltype(auto) with_system(System& sys, F&& f) {
  if constexpr (Shared) {
    system_ref<State> ref(sys);
    return f(ref);
  } else {
    return f(sys);
  }
}
template <class T>
inline constexpr bool is_system_ref = false;
template <class State>
inline constexpr bool is_system_ref<system_ref<State>> = true;

/// One whole step of a dense-output stepper, the last one aimed at t1
/// (odeint::integrate_adaptive's loop); a step size below tiny throws.
template <class Stepper, class System>
FLANGE_INLINE void dense_step(Stepper& st, System& sys, double t1, double tiny) {
  namespace odeint = boost::numeric::odeint;
  const double t = st.current_time();
  if (passes(t, st.current_time_step(), t1)) st.initialize(st.current_state(), t, t1 - t);
  try {
    st.do_step(std::ref(sys));
  } catch (const odeint::step_adjustment_error&) {
    throw step_collapse{t, static_cast<double>(st.current_time_step()), max_rejections};
  }
  if (std::abs(st.current_time_step()) < tiny && std::abs(t1 - st.current_time()) > tiny) [[unlikely]]
    throw step_collapse{st.current_time(), static_cast<double>(st.current_time_step()), 0};
}
/// The same for a type-erased system, out of line: a function of the
/// stepper and the state type only, which method.hpp names (FLANGE_COMMON)
/// for the default method and small states.
template <class Stepper, class State>
void dense_step_shared(Stepper& st, system_ref<State>& sys, double t1, double tiny) {
  dense_step(st, sys, t1, tiny);
}

/// A dense-output stepper: whole steps while they end before t1, then one
/// aimed at t1 (odeint::integrate_adaptive's loop); the state anywhere in
/// the last step from the stepper's interpolation.
template <class Stepper, class State>
class dense_stepping {
 public:
  static constexpr bool dense = true;
  explicit dense_stepping(Stepper st) : st_(std::move(st)) {}
  void start(const State& x, double t, double dt, double t1) {
    st_.initialize(x, t, dt);
    tiny_ = tiny_step(t, t1);
  }
  template <class System>
  FLANGE_INLINE void step(System& sys, double t1) {
    if constexpr (is_system_ref<System>) dense_step_shared(st_, sys, t1, tiny_);
    else dense_step(st_, sys, t1, tiny_);
  }
  void restart(const State& x) { st_.initialize(x, st_.current_time(), st_.current_time_step()); }
  const State& state() const { return st_.current_state(); }
  const State& previous_state() const { return st_.previous_state(); }
  double time() const { return st_.current_time(); }
  double previous_time() const { return st_.previous_time(); }
  /// The state at t inside the last step, from the stepper's interpolation.
  void at(double t, State& x) const { st_.calc_state(t, x); }

 private:
  mutable Stepper st_;  // some dense steppers' calc_state is not const
  double tiny_ = 0;
};

/// The adapter for an Odeint stepper, by its category.
template <class Stepper, class State>
auto stepping_for(Stepper st) {
  namespace odeint = boost::numeric::odeint;
  using category = typename odeint::unwrap_reference<Stepper>::type::stepper_category;
  if constexpr (std::is_base_of_v<odeint::dense_output_stepper_tag, category>)
    return dense_stepping<Stepper, State>(std::move(st));
  else if constexpr (std::is_base_of_v<odeint::controlled_stepper_tag, category>)
    return controlled_stepping<Stepper, State>(std::move(st));
  else {
    static_assert(std::is_base_of_v<odeint::stepper_tag, category>,
                  "flange: an integration takes a simple stepper (runge_kutta4), a controlled one "
                  "(make_controlled) or a dense-output one (make_dense_output)");
    return fixed_stepping<Stepper, State>(std::move(st));
  }
}

}  // namespace flange::detail
