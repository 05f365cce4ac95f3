// A scene as an Odeint system: the Scene's structure (scene/scene.hpp) with
// the constants the dynamics precompute (dynamics/model.hpp) and the state
// derivative.
//
//     auto arm = flange::scene(World<"world">{}, Revolute<"joint", axis::z>{}, …, connect<…>, …);
//     arm(x, dxdt, t);                      // ẋ = f(t, x): the Boost.Odeint system signature
//
// The state is x = (q, v): every joint's coordinates, then every joint's
// rates, joints in scene order. q̇ comes from each joint (q̇ = v for one-axis
// joints, a quaternion's rate for a Spherical joint), v̇ from the recursive
// algorithm the scene calls for (dynamics/algorithm.hpp).
#pragma once
#include "flange/detail/inline.hpp"
#include <array>
#include <string_view>
#include <type_traits>
#include <cmath>
#include <numbers>
#include <utility>

#include "flange/dynamics/algorithm.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/dynamics/momentum.hpp"
#include "flange/scene/scene.hpp"

namespace flange {

namespace detail {
struct from_scene_t {};
inline constexpr from_scene_t from_scene{};
}  // namespace detail

template <class S>
class System : public S {
 public:
  using scene_type = S;
  using model_type = detail::model_for<S>;

  /// From the scene's components, in order (flange::scene below).
  template <class... A>
  explicit System(std::in_place_t, A&&... components)
      : S(std::in_place, std::forward<A>(components)...), model_(detail::build_model(static_cast<const S&>(*this))) {
    if constexpr (detail::folded_mass_matrix<S>()) detail::fold_mass_matrix(*this, model_);
  }

  /// From a scene of the same components under another name (renamed
  /// below): the scene moved in, the constants computed again.
  System(detail::from_scene_t, S&& scene) : S(std::move(scene)), model_(detail::build_model(static_cast<const S&>(*this))) {
    if constexpr (detail::folded_mass_matrix<S>()) detail::fold_mass_matrix(*this, model_);
  }

  /// Constants the dynamics precompute (link inertias, set poses).
  [[nodiscard]] const model_type& model() const { return model_; }

  /// ẋ = f(x, t): q̇ from each joint, v̇ by the algorithm the scene's type
  /// calls for. Works for any container with data() and size() (std::array,
  /// std::vector, Eigen vectors) and any scalar type.
  template <class State, class T>
  FLANGE_INLINE void operator()(const State& x, State& dxdt, const T t) const {
    static_assert(detail::report_list<(S::topology.ok() ? S::tree.loop : -1), diagnostic::kinematic_loop,
                                      typename S::component_types>::value);
    static_assert(S::template report_cut_off<(S::topology.ok() && S::tree.loop < 0 ? S::tree.floating : -1),
                                             diagnostic::not_tied_through_joints>());
    static_assert(detail::report_list<(S::topology.ok() ? detail::first_uncuttable_joint<S>() : -1),
                                      diagnostic::joint_cannot_close_loop, typename S::component_types>::value);
    // Unless the scene has said what is missing: a small scene's derivative
    // is compiled into the caller (dynamics/algorithm.hpp, inline_derivative),
    // a larger one is called.
    if constexpr (S::joints_complete) {
      if constexpr (detail::inline_derivative<System>()) derivative_inline(x, dxdt, t);
      else derivative(x, dxdt, t);
    }
  }

 private:
  /// A larger scene's derivative: one function, called.
  template <class State, class T>
  void derivative(const State& x, State& dxdt, const T t) const {
    derivative_inline(x, dxdt, t);
  }
  /// ẋ = f(x, t), compiled into the caller.
  template <class State, class T>
  FLANGE_INLINE void derivative_inline(const State& x, State& dxdt, const T t) const {
    S::require_state_size(x);
    S::require_state_size(dxdt);
    using V = std::remove_cvref_t<decltype(x[0])>;
    const V* xs = x.data();
    V* d = dxdt.data();
    const V* q = xs;
    const V* v = xs + S::n_q;
    detail::joint_rates(static_cast<const S&>(*this), q, v, d);
    accelerations(*this, static_cast<V>(t), q, v, d + S::n_q);
  }

  model_type model_;
};

/// Builds a scene from components and connections, in any order: its
/// structure (scene/scene.hpp) and its dynamics.
template <class... Args>
auto scene(Args&&... args) {
  return detail::make_scene<System>(std::forward<Args>(args)...);
}

namespace detail {
/// The structure of a scene, built from components and connections as
/// flange::scene builds it, without its dynamics: the base of a named scene
/// (models/linkages.hpp), whose constants are then computed once, under the
/// short name, and never under the long one.
template <class... Args>
auto scene_structure(Args&&... args) {
  return make_scene<std::type_identity_t>(std::forward<Args>(args)...);
}
/// The scene Named (a class deriving from the structure S, adding nothing)
/// with its dynamics.
template <class Named, class S>
System<Named> named_system(S&& structure) {
  static_assert(std::is_base_of_v<S, Named> && sizeof(Named) == sizeof(S) && std::is_aggregate_v<Named>,
                "flange::renamed<Named>(scene): Named must be a class that derives from the scene's "
                "decltype(scene)::scene_type and adds nothing (struct Named : decltype(scene)::scene_type {};)");
  return System<Named>(from_scene, Named{std::move(structure)});
}
}  // namespace detail

/// The scene under a short name of its own: Named is a class that derives
/// from the scene's structure and adds nothing,
///
///     auto make_plant() { return scene(World<"world">{}, …); }
///     struct plant_scene : decltype(make_plant())::scene_type {};
///     const auto plant = renamed<plant_scene>(make_plant());
///
/// and every function the scene's dynamics instantiate carries
/// "plant_scene" in its mangled name where it carried the whole list of
/// components (tens of kilobytes for a scene of a few hundred, each mangled
/// again by the compiler): a large scene compiles in less time and memory,
/// and its object file shrinks (docs/performance.md, "Compile time at
/// scale"). The scene and its numbers are the same. The dynamics' constants
/// are computed under both names, once each.
template <class Named, class S>
System<Named> renamed(System<S> scene) {
  return detail::named_system<Named>(static_cast<S&&>(scene));
}

/// The state with every joint at its neutral configuration (angles and
/// offsets zero, quaternions the identity) and at rest.
template <class S>
typename S::state_type neutral_state(const S& scene) {
  typename S::state_type x{};
  detail::neutral_configuration(scene, x.data());
  return x;
}

namespace detail {
/// Whether normalize(scene, x) can change x: the scene has loops, or a joint
/// whose coordinates need keeping valid (a quaternion).
template <class S>
constexpr bool needs_projection() {
  return has_loops<S> || []<int... L>(std::integer_sequence<int, L...>) {
    return (false || ... || normalizes<typename S::template component_type<link_info<S, L + 1>::joint>>());
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}
}  // namespace detail

namespace detail {
/// normalize's projection; reports what the loops' part left (closure:
/// nothing in a scene without loops) for a caller that judges it.
template <class S, class State>
closure project_state(const S& scene, State& x) {
  S::require_state_size(x);
  detail::for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = detail::link_info<S, decltype(l)::value>;
    normalize_joint(scene.template component<LI::joint>(), x.data() + LI::q);
  });
  if constexpr (detail::has_loops<S>) {
    std::array<bool, S::n_v> free;
    free.fill(true);
    return detail::project_onto_loops(scene, x.data(), x.data() + S::n_q, free);
  } else {
    return {};
  }
}
}  // namespace detail

/// Keeps every joint's coordinates valid (a quaternion back to unit norm)
/// and, in a scene with loops, (q, v) on the loops' constraints (Newton on
/// Φ(q) = 0, then G·v = 0, each the least change: dynamics/loop_solve.hpp): a
/// projection between steps. Every integration path but the raw Odeint one
/// does it after each step and judges the result (simulate/integrate.hpp);
/// this one does not judge.
template <class S, class State>
void normalize(const S& scene, State& x) {
  (void)detail::project_state(scene, x);
}

namespace detail {
/// The joint named Name in scene S, checked at compile time (a misspelt
/// name is one error listing the valid ones, scene/named_state.hpp).
template <class S, fixed_string Name>
struct named_joint {
  static constexpr int found = joint_named<S, Name>();
  static constexpr int index = found >= 0 ? found : joint_indices<S>()[0];  // no second error after the first
  using type = typename S::template component_type<index>;
};
/// The component index of the joint named Name, a cut one too (−1 after
/// one diagnostic listing the valid names).
template <class S, fixed_string Name>
constexpr int any_joint_named() {
  constexpr int c = S::index_of(Name.view());
  if constexpr (c >= 0 && S::tree.cut_of[c < 0 ? 0 : c] >= 0) return c;
  else return joint_named<S, Name>();
}
/// The joint named Name in scene S, cut or not: cut is its cut's index (−1
/// for a joint of the tree).
template <class S, fixed_string Name>
struct named_any_joint {
  static constexpr int found = any_joint_named<S, Name>();
  static constexpr int index = found >= 0 ? found : joint_indices<S>()[0];
  static constexpr int cut = found >= 0 ? S::tree.cut_of[index] : -1;
  using type = typename S::template component_type<index>;
  /// Whether close_loops can hold it: a tree joint, or a cut one whose
  /// coordinates are its rates' integrals (not a quaternion); otherwise one
  /// diagnostic.
  static constexpr bool holdable = [] {
    if constexpr (cut >= 0 && type::nq != type::nv) {
      (void)sizeof(diagnostic::cut_joint_cannot_be_held<diagnostic::member<Name>>);
      return false;
    } else {
      return true;
    }
  }();
};
/// The cuts among the joints named, in the order named, as held_cuts
/// (dynamics/loop_solve.hpp).
template <class S, fixed_string... Names>
struct held_cuts_of {
  static constexpr std::array<int, sizeof...(Names)> all{
      (named_any_joint<S, Names>::holdable ? named_any_joint<S, Names>::cut : -1)...};
  static constexpr int count = [] {
    int c = 0;
    for (const int k : all) c += k >= 0;
    return c;
  }();
  static constexpr std::array<int, count> cuts = [] {
    std::array<int, count> r{};
    int i = 0;
    for (const int k : all)
      if (k >= 0) r[i++] = k;
    return r;
  }();
  template <std::size_t... I>
  static auto make(std::index_sequence<I...>) -> held_cuts<S, cuts[I]...>;
  using type = decltype(make(std::make_index_sequence<count>{}));
};

/// Whether component I is a body that joint C carries (C's link or a link
/// beyond it).
template <class S, int C>
constexpr bool carried_by(int i) {
  int l = S::tree.set_link[S::topology.set_of[S::table.frame_base[i]]];
  for (; l > 0; l = S::tree.link_parent[l])
    if (l == S::tree.link_of_joint[C]) return true;
  return false;
}
/// Joint C's translation rates (its first three, frame_b's velocity in
/// frame_a coordinates, relative to frame_a) such that the centre of mass
/// of everything C carries moves at v_cm (the same terms), every other rate
/// in x as it is. That velocity is v_cm(0) + v, v_cm(0) what it is with the
/// three at zero: so v = v_cm − v_cm(0), from the frames at x.
template <class S, class State, int C>
void set_centre_of_mass_velocity(const S& scene, State& x, const Vec3d& v_cm) {
  double* v = &x[S::n_q + S::tree.v_offset[C]];
  for (int i = 0; i < 3; ++i) v[i] = 0;
  const frames_at_state<S, double> at(scene, x);
  const auto carried = momentum_of(scene, at, [](int i) { return carried_by<S, C>(i); });
  if (!(carried.m > 0))
    throw parameter_error(concat(S::table.type_names[C], " \"", S::table.names[C], "\": v_cm is given, but the joint ",
                                 "carries no mass, so it has no centre of mass"));
  const auto& a = at.frames[S::table.frame_base[C]];  // frame_a: k.R world → frame_a, k.w in frame_a's axes
  const Vec3d r_cm = carried.first_moment / carried.m, v_cm0_world = carried.h.linear / carried.m;
  const Vec3d v_cm0 = a.R * (v_cm0_world - a.v) - a.w.cross(a.R * (r_cm - a.r));
  for (int i = 0; i < 3; ++i) v[i] = v_cm[i] - v_cm0[i];
}
template <class S, class State, int C>
void write_joint(const S& scene, State& x, const joint_state_t<typename S::template component_type<C>>& value) {
  std::array<double, S::template component_type<C>::nq> q;
  std::array<double, S::template component_type<C>::nv> v;
  write_joint_state(scene.template component<C>(), value, q.data(), v.data());
  for (std::size_t i = 0; i < q.size(); ++i) x[S::tree.q_offset[C] + i] = q[i];
  for (std::size_t i = 0; i < v.size(); ++i) x[S::n_q + S::tree.v_offset[C] + i] = v[i];
}
/// After every joint is written: a centre-of-mass velocity where one was given.
template <class S, class State, int C>
void finish_joint(const S& scene, State& x, const joint_state_t<typename S::template component_type<C>>& value) {
  if constexpr (requires { value.v_cm; })
    if (value.v_cm) set_centre_of_mass_velocity<S, State, C>(scene, x, *value.v_cm);
}
}  // namespace detail

/// Sets the named joint's coordinates and rates in x from its state type
/// (Revolute: {.q, .v}; Spherical: {.R = orientation::…, .w}; FreeMotion:
/// {.r, .v, .R, .w}, or .v_cm, the velocity of the centre of mass of all it
/// carries, instead of .v; Universal, Cylindrical, Planar: {.q = {…}, .v =
/// {…}}), checked: an orientation must be a rotation, every number finite.
template <fixed_string Name, class S, class State>
void set_joint(const S& scene, State& x, const joint_state_t<typename detail::named_joint<S, Name>::type>& value) {
  S::require_state_size(x);
  detail::write_joint<S, State, detail::named_joint<S, Name>::index>(scene, x, value);
  detail::finish_joint<S, State, detail::named_joint<S, Name>::index>(scene, x, value);
}

/// The named joint's state in its own terms, read from x: what set_joint
/// writes (Revolute: {.q, .v}; Spherical: {.R, .w}; FreeMotion: {.r, .v, .R,
/// .w}, the quaternion as a rotation matrix; Universal, Cylindrical, Planar:
/// {.q = {…}, .v = {…}}). The name is checked at compile time. A cut joint
/// (one that closes a loop) reads as its frames place it, as recover gives
/// it: its angles within (−π, π].
template <fixed_string Name, class S, class State>
[[nodiscard]] joint_state_t<typename detail::named_any_joint<S, Name>::type> get_joint(const S& scene,
                                                                                     const State& x) {
  S::require_state_size(x);
  using N = detail::named_any_joint<S, Name>;
  constexpr int C = N::index;
  if constexpr (N::cut >= 0) {
    const auto r = detail::read_cut_at<S, N::cut>(scene, x.data(), x.data() + S::n_q);
    return read_joint_value(scene.template component<C>(), r.q.data(), r.v.data());
  } else {
    using J = typename S::template component_type<C>;
    std::array<double, J::nq> q;
    std::array<double, J::nv> v;
    for (int i = 0; i < J::nq; ++i) q[i] = x[S::tree.q_offset[C] + i];
    for (int i = 0; i < J::nv; ++i) v[i] = x[S::n_q + S::tree.v_offset[C] + i];
    return read_joint_value(scene.template component<C>(), q.data(), v.data());
  }
}

namespace detail {
/// q[k] + 2π·m for the integer m that brings it nearest to guess[k], for
/// each angle k of joint J (periodic_coordinates); other coordinates as they are.
template <class J>
void unwrap_angles(double* q, const double* guess) {
  constexpr auto angles = periodic_coordinates<J>();
  constexpr double turn = 2 * std::numbers::pi;
  for (int k = 0; k < J::nq; ++k)
    if (angles[k]) q[k] += turn * std::round((guess[k] - q[k]) / turn);
}
}  // namespace detail

/// get_joint, with a cut joint's angles (periodic_coordinates: a Revolute's
/// φ, a Universal's φ₁ and φ₂, a Cylindrical's or Planar's turn) taken
/// within half a turn of near's: along a run, give the reading of the sample
/// before, and the angle is continuous wherever the joint turns less than
/// half a turn between the two samples (get_joint of a trajectory,
/// simulate/simulate.hpp, does this with the rates). A tree joint's angles
/// are state coordinates, continuous already: it reads as get_joint.
template <fixed_string Name, class S, class State>
[[nodiscard]] joint_state_t<typename detail::named_any_joint<S, Name>::type> get_joint(
    const S& scene, const State& x, const joint_state_t<typename detail::named_any_joint<S, Name>::type>& near) {
  using N = detail::named_any_joint<S, Name>;
  if constexpr (N::cut >= 0) {
    S::require_state_size(x);
    using J = typename N::type;
    const auto& joint = scene.template component<N::index>();
    std::array<double, J::nq> gq;
    std::array<double, J::nv> gv;
    write_joint_state(joint, near, gq.data(), gv.data());
    auto r = detail::read_cut_at<S, N::cut>(scene, x.data(), x.data() + S::n_q);
    detail::unwrap_angles<J>(r.q.data(), gq.data());
    return read_joint_value(joint, r.q.data(), r.v.data());
  } else {
    return get_joint<Name>(scene, x);
  }
}

namespace detail {
template <fixed_string... Held, class S, class State, class H>
void close_holding(const S& scene, State& x, const H& held);
}  // namespace detail

/// The state with the named joints set and every other joint at its neutral
/// configuration and at rest:
///
///   auto x0 = initial_state<"shoulder", "elbow">(arm, {.q = 0.3}, {.q = -0.2, .v = 1});
///
/// Each value has its joint's state type (see set_joint); the names are
/// checked at compile time, and a name given twice is an error. A joint
/// that closes a loop (cut) may be named too: the loops are then closed
/// with every named joint held at its value (close_loops), the cut ones as
/// their frames place them.
template <fixed_string... Names, class S>
typename S::state_type initial_state(const S& scene,
                                     const joint_state_t<typename detail::named_any_joint<S, Names>::type>&... values) {
  constexpr std::array<int, sizeof...(Names)> idx{detail::named_any_joint<S, Names>::index...};
  constexpr int twice = [&] {
    for (std::size_t i = 0; i < idx.size(); ++i)
      for (std::size_t j = i + 1; j < idx.size(); ++j)
        if (idx[i] == idx[j]) return int(i);
    return -1;
  }();
  if constexpr (twice >= 0) {
    constexpr std::array<std::string_view, sizeof...(Names)> names{Names.view()...};
    (void)sizeof(diagnostic::joint_named_twice<
                 diagnostic::member<fixed_string<names[twice].size() + 1>(names[twice])>, void>);
  }
  using State = typename S::state_type;
  auto x = neutral_state(scene);
  using H = typename detail::held_cuts_of<S, Names...>::type;
  H held;
  [[maybe_unused]] int row = 0;  // (unused when no cut joint is named)
  ((void)[&] {
    using N = detail::named_any_joint<S, Names>;
    if constexpr (N::cut < 0) {
      detail::write_joint<S, State, N::index>(scene, x, values);
    } else {
      using J = typename N::type;
      std::array<double, J::nq> q;
      std::array<double, J::nv> v;
      write_joint_state(scene.template component<N::index>(), values, q.data(), v.data());
      if constexpr (N::holdable)
        for (int i = 0; i < J::nv; ++i, ++row) held.q[row] = q[i], held.v[row] = v[i];
    }
  }(), ...);
  ((void)[&] {
    using N = detail::named_any_joint<S, Names>;
    if constexpr (N::cut < 0) detail::finish_joint<S, State, N::index>(scene, x, values);
  }(), ...);
  if constexpr (H::rows > 0) detail::close_holding<Names...>(scene, x, held);
  return x;
}

/// Throws parameter_error naming the joint if some joint's coordinates are
/// not valid (a quaternion far from unit norm): an input mistake, not drift.
template <class S, class State>
void check_coordinates(const S& scene, const State& x) {
  detail::for_links<S>([&](auto l) {
    using LI = detail::link_info<S, decltype(l)::value>;
    const auto& j = scene.template component<LI::joint>();
    check_joint_coordinates(j, x.data() + LI::q);
  });
}

namespace detail {
/// The loop the constraint row lies in, for a message: its cut joint.
template <class S>
std::string describe_loop(const S& scene, int row) {
  return concat("the loop closed by ", describe_component(scene, S::tree.cuts[row < 0 ? 0 : cut_of_row<S>(row)]));
}
/// How far a loop is open: a translation row in metres, a rotation row as an angle.
template <class S>
std::string loop_gap(int row, double phi) {
  const int k = cut_of_row<S>(row);
  bool translation = false;
  for_cuts<S>([&](auto c) {
    using CI = cut_info<S, decltype(c)::value>;
    if (decltype(c)::value == k) translation = row < cut_row<S, decltype(c)::value>() + CI::translation_rows;
  });
  return translation ? concat(phi, " m apart") : concat(phi, " rad out of line");
}
/// Throws parameter_error if a loop of the state is closed with its cut
/// joint turned over (cut_alignment, loops.hpp): its frames meet the rows
/// with the joint's axis reversed, which is not the mechanism written.
template <class S>
void check_not_turned_over(const S& scene, const double* q, const double* v, const char* advice) {
  if (const int k = turned_over_cut(scene, q); k >= 0)
    throw parameter_error(concat("flange: the state closes the loop closed by ",
                                 describe_component(scene, S::tree.cuts[k]),
                                 " only with that joint turned over (its frame_b half a turn from where the joint "
                                 "can put it: its axis reversed); ",
                                 advice, "; ", describe_state(q, S::n_q, v, S::n_v)));
}
/// The largest |Φ| a state may have and still be taken as closed.
template <class S>
double closure_tolerance(const S& scene) {
  return 1e-9 * length_scale(scene);
}
}  // namespace detail

namespace detail {
/// The cut joints among Names, quoted, for a message.
template <class S, fixed_string... Names>
std::string held_names() {
  std::string r;
  ((named_any_joint<S, Names>::cut >= 0 ? (void)(r += concat(r.empty() ? "" : ", ", "\"", Names.view(), "\"")) : void()),
   ...);
  return r;
}

/// close_loops with the cut joints' targets in held (held_cuts_of<S, Held...>).
template <fixed_string... Held, class S, class State, class H>
void close_holding(const S& scene, State& x, const H& held) {
  std::array<bool, S::n_v> free;
  free.fill(true);
  ((void)[&] {
    using N = named_any_joint<S, Held>;
    if constexpr (N::cut < 0)
      for (int i = 0; i < N::type::nv; ++i) free[S::tree.v_offset[N::index] + i] = false;
  }(), ...);
  constexpr int mc = n_constraints<S>();
  if constexpr (mc + H::rows > 0) {
    const auto r = project_onto_loops(scene, x.data(), x.data() + S::n_q, free, held);
    const double tol = closure_tolerance(scene);
    if (!(r.phi <= tol)) {
      if (r.worst_row >= mc)
        throw parameter_error(concat("flange: the cut joints held (", held_names<S, Held...>(),
                                     ") cannot be placed as asked while the loops close: a coordinate stays ", r.phi,
                                     " off after ", r.iterations,
                                     " Newton steps (the mechanism cannot reach it, or the held joints fix it "
                                     "otherwise); ",
                                     describe_state(x.data(), S::n_q, x.data() + S::n_q, S::n_v)));
      throw parameter_error(concat("flange: ", describe_loop(scene, r.worst_row),
                                   " cannot close near the given state: its frames stay ",
                                   loop_gap<S>(r.worst_row, r.phi), " after ", r.iterations,
                                   " Newton steps (the links cannot meet there, or the guess is past a "
                                   "dead point); ",
                                   describe_state(x.data(), S::n_q, x.data() + S::n_q, S::n_v)));
    }
    check_not_turned_over(scene, x.data(), x.data() + S::n_q,
                          "Newton's method found that assembly nearest the guess: give a guess nearer the one meant");
    if (!(r.phid <= tol))
      throw parameter_error(concat("flange: the loops cannot move at the rates held (", r.phid,
                                   " left in G·v): the held joints' rates are not a motion of the "
                                   "mechanism, or it is at a dead point; ",
                                   describe_state(x.data(), S::n_q, x.data() + S::n_q, S::n_v)));
  }
}
}  // namespace detail

/// Closes the scene's loops from the joints named (held: their coordinates
/// and rates are kept) by changing the others as little as possible:
///
///   auto x = initial_state<"crank_pivot">(fourbar, {.q = 1.0, .v = 2.0});
///   close_loops<"crank_pivot">(fourbar, x);   // the coupler and rocker follow
///
/// The other joints' coordinates in x are the guess; Newton's method finds
/// the closed position nearest to it, then the rates with G·v = 0. A cut
/// joint named is held as x's frames place it (get_joint), as if its loop
/// were closed there; a cut Spherical or FreeMotion cannot be held. Throws
/// parameter_error naming the loop if it cannot close near the guess (links
/// too short to meet, or a guess past a dead point), or if the held rates
/// cannot be met.
template <fixed_string... Held, class S, class State>
void close_loops(const S& scene, State& x) {
  S::require_state_size(x);
  using H = typename detail::held_cuts_of<S, Held...>::type;
  H held;
  [[maybe_unused]] int row = 0;  // (unused when no cut joint is named)
  ((void)[&] {
    using N = detail::named_any_joint<S, Held>;
    if constexpr (N::cut >= 0 && N::holdable) {
      const auto r = detail::read_cut_at<S, N::cut>(scene, x.data(), x.data() + S::n_q);
      for (int i = 0; i < N::type::nv; ++i, ++row) held.q[row] = r.q[i], held.v[row] = r.v[i];
    }
  }(), ...);
  detail::close_holding<Held...>(scene, x, held);
}

/// The number of constraint rows of scene type S's loops (0 without loops):
/// the length of loop_residual's Φ.
template <class S>
inline constexpr int constraint_count = detail::n_constraints<S>();

/// The names of the joints scene type S cut, one per loop, in the order
/// the scene lists them (docs/loops.md, "How loops are found and cut").
template <class S>
constexpr std::array<std::string_view, S::tree.n_cuts> cut_joints() {
  std::array<std::string_view, S::tree.n_cuts> names{};
  for (int k = 0; k < S::tree.n_cuts; ++k) names[k] = S::table.names[S::tree.cuts[k]];
  return names;
}

/// How far a state is off the scene's loop constraints, row by row: Φ(q)
/// (metres for a translation row, radians for a rotation row) and
/// Φ̇ = G·v. Rows come cut joint by cut joint, in the order of the cuts
/// (docs/loops.md). A scene without loops has no rows.
template <int M>
struct loop_residuals {
  std::array<double, M> phi{}, phid{};
  /// max |Φ_i| (0 without rows)
  [[nodiscard]] double max_phi() const { return max_abs(phi); }
  /// max |Φ̇_i| (0 without rows)
  [[nodiscard]] double max_phid() const { return max_abs(phid); }

 private:
  static double max_abs(const std::array<double, M>& a) {
    double m = 0;
    for (double e : a) m = std::abs(e) > m || std::isnan(e) ? std::abs(e) : m;
    return m;
  }
};

/// Φ(q) and G·v at the state x (see loop_residuals).
template <class S, class State>
loop_residuals<detail::n_constraints<S>()> loop_residual(const S& scene, const State& x) {
  S::require_state_size(x);
  loop_residuals<detail::n_constraints<S>()> r;
  if constexpr (detail::has_loops<S>) {
    const auto k = detail::loop_kinematics<S>(scene, x.data(), x.data() + S::n_q);
    r.phi = k.phi;
    r.phid = k.phid;
  } else {
    (void)scene;
  }
  return r;
}

/// The rank of a scene's loop constraints at a state, and what it leaves.
struct loop_rank_info {
  int rows = 0;  ///< the constraint rows (constraint_count)
  int rank = 0;  ///< the independent ones: fewer where rows repeat others
  int dof = 0;   ///< the tree's rates less the rank: the mechanism's degrees of freedom there
};

/// The rank of G at x (rows in comparable units, a row counted when its
/// part independent of the others is above 1e-5 of the largest): Bricard's
/// linkage has 5 rows of rank 4 and 1 degree of freedom, a planar four-bar
/// written with run-time axes 5 rows of rank 2. A scene without loops has
/// no rows and its tree's rates as degrees of freedom.
template <class S, class State>
loop_rank_info loop_rank(const S& scene, const State& x) {
  S::require_state_size(x);
  constexpr int m = detail::n_constraints<S>(), n = S::n_v;
  loop_rank_info r{m, 0, n};
  if constexpr (detail::has_loops<S>) {
    const auto k = detail::loop_kinematics<S>(scene, x.data(), x.data() + S::n_q);
    const auto units = detail::row_units(scene);
    Eigen::Matrix<double, m, m> A;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        double a = 0;
        for (int c = 0; c < n; ++c) a += k.G(i, c) * k.G(j, c);
        A(i, j) = units[i] * units[j] * a;
      }
    std::array<double, m> zero{}, y;
    r.rank = detail::solve_semidefinite<m>(A, zero.data(), y.data());
    r.dof = n - r.rank;
  }
  return r;
}

/// Throws parameter_error naming the loop if the state does not close the
/// scene's loops (|Φ| above closure_tolerance): a state set by hand usually
/// does not; close_loops makes one that does.
template <class S, class State>
void check_loops(const S& scene, const State& x) {
  if constexpr (detail::has_loops<S>) {
    std::array<double, S::n_v> zero{};
    const auto k = detail::loop_kinematics<S>(scene, x.data(), zero.data());
    for (int i = 0; i < detail::n_constraints<S>(); ++i)
      if (!(std::abs(k.phi[i]) <= detail::closure_tolerance(scene)))
        throw parameter_error(detail::concat(
            "flange: the state leaves ", detail::describe_loop(scene, i), " open: its frames are ",
            detail::loop_gap<S>(i, std::abs(k.phi[i])), "; set the independent joints and call close_loops<…>(scene, x); ",
            detail::describe_state(x.data(), S::n_q, x.data() + S::n_q, S::n_v)));
    detail::check_not_turned_over(scene, x.data(), x.data() + S::n_q,
                                  "set the independent joints and call close_loops<…>(scene, x) from a guess near the "
                                  "assembly meant");
  } else {
    (void)scene;
    (void)x;
  }
}

}  // namespace flange
