// Scene: components and connections composed at compile time.
//
//     auto arm = flange::scene(
//         World<"world">{}, Torque<"motor">({.M_ext = M}), Revolute<"joint", axis::z>{},
//         FixedTranslation<"rod">({.d = {d, 0, 0}}), Body<"mass">({.m = m, .J = J}),
//         connect<"world.frame_b", "joint.frame_a">, connect<"world.frame_b", "motor.frame_a">,
//         connect<"joint.frame_b", "rod.frame_a">, connect<"joint.frame_b", "motor.frame_b">,
//         connect<"rod.frame_b", "mass.frame_a">);
//
// The scene's type carries its whole structure; its value carries parameters.
// Everything structural (connection sets, counts, layout of the flattened DAE
// vector, kinematic tree, the state layout) is a constant expression, checked
// by static_asserts whose messages name the culprit (scene/diagnostics.hpp).
//
// This layer knows structure only. The state derivative, the precomputed
// dynamics constants and the Odeint system are added on top of a Scene by
// flange::System (simulate/system.hpp), which flange::scene(...) returns.
#pragma once
#include <array>
#include <string_view>
#include <type_traits>
#include <utility>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/mask.hpp"
#include "flange/detail/type_list.hpp"
#include "flange/scene/connect.hpp"
#include "flange/scene/diagnostics.hpp"
#include "flange/scene/named_state.hpp"
#include "flange/scene/joint_check.hpp"
#include "flange/scene/topology.hpp"
#include "flange/scene/wiring.hpp"

namespace flange {

namespace detail {
/// Instantiates Diag<the I-th of Ts> when I ≥ 0, which fails with its message.
template <int I, template <class...> class Diag, class... Ts>
constexpr bool report() {
  if constexpr (I >= 0) (void)sizeof(Diag<nth_t<I, Ts...>>);
  return true;
}

/// report<I, Diag, Ts...> over a type_list<Ts...>.
template <int I, template <class...> class Diag, class List>
struct report_list;
template <int I, template <class...> class Diag, class... Ts>
struct report_list<I, Diag, type_list<Ts...>> {
  static constexpr bool value = report<I, Diag, Ts...>();
};

template <class E>
struct equation_count;
template <class... E>
struct equation_count<boost::hana::tuple<E...>> {
  static constexpr int value = (0 + ... + E::size);
};

template <class C>
constexpr int equations_of() {
  return equation_count<decltype(std::declval<const C&>().equations())>::value;
}
template <class C>
constexpr int internal_unknowns() {
  int n = 0;
  for (const auto& i : C::internals) n += expr::unknown_count(i.kind);
  return n;
}
template <class C>
constexpr int internal_storage() {
  int n = 0;
  for (const auto& i : C::internals) n += expr::storage_size(i.kind);
  return n;
}
template <class C>
constexpr bool locally_balanced() {
  // Modelica's rule: a component's own equations number its unknowns minus
  // the flow variables of its connectors (those come from the connections).
  return equations_of<C>() == internal_unknowns<C>() + 12 * int(C::frames.size()) - 6 * int(C::frames.size());
}
/// The size of a state type when its type fixes it (std::array, fixed-size
/// Eigen vectors), else −1 (std::vector, dynamic Eigen vectors).
template <class State>
constexpr int static_size() {
  if constexpr (requires { std::tuple_size<State>::value; }) return int(std::tuple_size<State>::value);
  else if constexpr (requires { State::SizeAtCompileTime; }) return State::SizeAtCompileTime < 0 ? -1 : int(State::SizeAtCompileTime);
  else return -1;
}

template <class C>
constexpr int needed_equations() {
  return internal_unknowns<C>() + 6 * int(C::frames.size());
}
}  // namespace detail

inline constexpr int frame_storage = 18;  // r (3), R (9), F (3), M (3)
inline constexpr std::array<int, 4> frame_var_offset{0, 3, 12, 15};

template <class Components, class Connections>
class Scene;

template <Component... Cs, int... F>
class Scene<detail::type_list<Cs...>, detail::wiring<F...>> {
 public:
  static constexpr int n_components = sizeof...(Cs);
  static constexpr int n_connections = detail::wiring<F...>::n_connections;
  static constexpr int n_frames = (0 + ... + int(Cs::frames.size()));
  using component_types = detail::type_list<Cs...>;
  template <int I>
  using component_type = detail::nth_t<I, Cs...>;

 private:
  static constexpr auto make_table() {
    auto t = detail::component_table_v<n_connections, Cs...>;
    t.conn = detail::wiring<F...>::frames;
    return t;
  }

 public:
  static constexpr auto table = make_table();
  static constexpr auto topology = detail::analyze(table, detail::name_index_v<n_connections, Cs...>);
  static constexpr auto tree = detail::build_tree(table, topology);

  // ---------------------------------------------------------- diagnostics
  // (A connection naming no frame was reported as the names were resolved:
  // scene/wiring.hpp.)
 private:
  /// Diag<connection K, as the user wrote it>, when K ≥ 0.
  template <int K, template <class...> class Diag>
  static constexpr bool report_connection() {
    if constexpr (K >= 0)
      (void)sizeof(Diag<detail::connection_of<table, table.conn[2 * K], table.conn[2 * K + 1]>>);
    return true;
  }

 public:
  // A name given twice comes first, and alone: connections naming it reach
  // only the first component of that name, so the redundant connection and
  // the cut-off component that follow are its symptoms, not more mistakes.
  static_assert((detail::report<topology.duplicate_name, diagnostic::duplicate_component_name, Cs...>()));
  static_assert(report_connection<topology.self_connection, diagnostic::frame_listed_twice_in_connection>());
  static_assert(report_connection<topology.duplicate_name < 0 ? topology.redundant_connection : -1,
                                  diagnostic::frame_connected_twice_in_one_set>());
  static_assert((detail::report<topology.n_worlds == 0 ? 0 : -1, diagnostic::no_world, detail::type_list<Cs...>>()));
  static_assert((detail::report<topology.second_world, diagnostic::two_worlds, Cs...>()));
  /// Frame k of component c that no connection names (−1 if none).
  static constexpr int unconnected_frame(int c) {
    if (c < 0) return -1;
    for (int k = 0; k < table.nframes[c]; ++k) {
      bool named = false;
      for (int f : table.conn) named = named || f == table.frame_base[c] + k;
      if (!named) return k;
    }
    return -1;
  }
  /// Reports component C (≥ 0) as cut off from the World: as a frame left
  /// unconnected if one of its frames is, else by Diag (the wider reason).
  template <int C, template <class...> class Diag>
  static constexpr bool report_cut_off() {
    if constexpr (C >= 0) {
      using Comp = component_type<C>;
      constexpr int k = unconnected_frame(C);
      if constexpr (k >= 0)
        (void)sizeof(diagnostic::frame_connected_to_nothing<
                     Comp, diagnostic::member<fixed_string<Comp::frames[k].size() + 1>(Comp::frames[k])>>);
      else (void)sizeof(Diag<Comp>);
    }
    return true;
  }
  // Only when the connections themselves were fine: a misspelt one leaves
  // its component unreached, and that is not a second mistake.
  static_assert(report_cut_off<(topology.n_worlds == 1 && topology.bad_name_connection < 0 &&
                                        topology.self_connection < 0 && topology.duplicate_name < 0
                                    ? topology.unreached
                                    : -1),
                               diagnostic::not_connected_to_world>());
  static_assert((detail::check_joints<Cs...>()));
  /// Whether every joint models the joint concept (core/joint.hpp).
  static constexpr bool joints_complete = (detail::complete_joint<Cs>() && ...);

 private:
  /// The first joint whose type cannot be connected frame_b toward the World but is.
  static constexpr int first_backwards_joint() {
    int i = 0, found = -1;
    (
        [&] {
          if constexpr (Cs::kind == role::joint) {
            if constexpr (joint_requirements::reversible<Cs>) {
              if (!Cs::reversible && found < 0 && tree.link_of_joint[i] >= 0 && tree.link_dir[tree.link_of_joint[i]] < 0)
                found = i;
            }
          }
          ++i;
        }(),
        ...);
    return found;
  }

 public:
  static_assert(detail::report<topology.ok() ? first_backwards_joint() : -1, diagnostic::joint_connected_backwards,
                               Cs...>());

  // A line force needs its two ends apart.
 private:
  static constexpr int first_collapsed_force() {
    int i = 0, found = -1;
    (
        [&] {
          if constexpr (Cs::kind == role::force && int(Cs::frames.size()) == 2) {
            if constexpr (requires { Cs::line_of_action; }) {
              if (Cs::line_of_action && found < 0 &&
                  topology.set_of[table.frame_base[i]] == topology.set_of[table.frame_base[i] + 1])
                found = i;
            }
          }
          ++i;
        }(),
        ...);
    return found;
  }
  static constexpr int first_load_on_world() {
    int i = 0, found = -1;
    ((Cs::kind == role::force && Cs::frames.size() == 1 && found < 0 &&
              topology.set_of[table.frame_base[i]] == topology.set_of[table.frame_base[topology.world]]
          ? found = i
          : 0,
      ++i),
     ...);
    return found;
  }

  // A contact pairs shapes on two bodies: on one (its frames on one link of
  // the tree) they could never touch.
  static constexpr int first_contact_on_one_body() {
    int i = 0, found = -1;
    (
        [&] {
          if constexpr (requires { Cs::pairs_two_bodies; }) {
            const int a = tree.set_link[topology.set_of[table.frame_base[i]]];
            const int b = tree.set_link[topology.set_of[table.frame_base[i] + 1]];
            if (Cs::pairs_two_bodies && found < 0 && a >= 0 && a == b) found = i;
          }
          ++i;
        }(),
        ...);
    return found;
  }

 public:
  static_assert(detail::report<topology.ok() ? first_collapsed_force() : -1, diagnostic::force_ends_in_one_set,
                               Cs...>());
  static_assert(detail::report<topology.ok() && tree.loop < 0 && tree.floating < 0 ? first_contact_on_one_body() : -1,
                               diagnostic::contact_on_one_body, Cs...>());
  static_assert(detail::report<topology.ok() ? first_load_on_world() : -1, diagnostic::world_load_on_world, Cs...>());

  // ---------------------------------------------------------- counts
 private:
  static constexpr int first_unbalanced() {
    int i = 0, found = -1;
    ((found < 0 && !detail::locally_balanced<Cs>() ? found = i : 0, ++i), ...);
    return found;
  }
  template <int I>
  static constexpr bool report_unbalanced() {
    if constexpr (I >= 0) {
      using C = component_type<I>;
      (void)sizeof(diagnostic::unbalanced_component<C, diagnostic::equations_declared<detail::equations_of<C>()>,
                                                    diagnostic::equations_needed<detail::needed_equations<C>()>>);
    }
    return true;
  }

 public:
  static constexpr int n_component_equations = (0 + ... + detail::equations_of<Cs>());
  static constexpr int n_connection_equations = [] {
    int n = 0;
    for (int s = 0; s < topology.n_sets; ++s) n += 6 * (topology.set_size[s] - 1) + 6;
    return n;
  }();
  static constexpr int n_equations = n_component_equations + n_connection_equations;
  static constexpr int n_unknowns = 12 * n_frames + (0 + ... + detail::internal_unknowns<Cs>());
  static_assert(report_unbalanced<first_unbalanced()>());
  static_assert((detail::report<(first_unbalanced() < 0 && n_equations != n_unknowns) ? 0 : -1,
                                diagnostic::unbalanced_scene,
                                detail::type_list<diagnostic::equations_declared<n_equations>, diagnostic::unknowns<n_unknowns>>>()));

  // ---------------------------------------------------------- layout
  /// Length of the flattened variable vector y: every frame's r, R (stored as
  /// 9 numbers, counted as 3 unknowns), F, M, then the components' internals.
  static constexpr int n_storage = frame_storage * n_frames + (0 + ... + detail::internal_storage<Cs>());
  static constexpr std::array<int, n_components> internal_base = [] {
    std::array<int, n_components> b{};
    int c = 0, off = frame_storage * n_frames;
    ((b[c++] = off, off += detail::internal_storage<Cs>()), ...);
    return b;
  }();

  /// Offset in y of local slot `slot` of component CI.
  template <int CI>
  static constexpr int slot_offset(int slot) {
    using C = component_type<CI>;
    constexpr int nf = int(C::frames.size());
    if (slot < 4 * nf) return frame_storage * (table.frame_base[CI] + slot / 4) + frame_var_offset[slot % 4];
    int off = internal_base[CI];
    for (int i = 0; i < slot - 4 * nf; ++i) off += expr::storage_size(C::internals[i].kind);
    return off;
  }
  /// Offset in y of variable `which` (0 r, 1 R, 2 F, 3 M) of global frame f.
  static constexpr int frame_offset(int f, int which) { return frame_storage * f + frame_var_offset[which]; }

  /// Index of the component with this name (a constant expression).
  static constexpr int index_of(std::string_view name) {
    for (int c = 0; c < n_components; ++c)
      if (table.names[c] == name) return c;
    return -1;
  }
  /// Global index of the frame "component.frame".
  static constexpr int frame_index(std::string_view name) {
    return detail::find_frame(table, name, detail::name_index_v<n_connections, Cs...>);
  }

  // ---------------------------------------------------------- joints and the state
  /// The number of joint coordinates q and of joint rates v (they differ for
  /// quaternions), joints in scene order.
  static constexpr int n_q = tree.n_q;
  static constexpr int n_v = tree.n_v;
  static constexpr int n_joints = tree.n_joints;
  /// Where the named joint's coordinates start in q (x[q_offset]) and its
  /// rates in v (x[n_q + v_offset]), checked at compile time: a misspelt name
  /// is one error with "did you mean", a cut joint (it has no coordinates in
  /// the state) one that says so.
  template <fixed_string Joint>
  static constexpr int q_offset() {
    constexpr int c = detail::joint_named<Scene, Joint>();
    return c < 0 ? 0 : tree.q_offset[c];
  }
  template <fixed_string Joint>
  static constexpr int v_offset() {
    constexpr int c = detail::joint_named<Scene, Joint>();
    return c < 0 ? 0 : tree.v_offset[c];
  }
  /// The same for a name known at run time: a name that is not a joint of
  /// the tree throws parameter_error with "did you mean" (in a constant
  /// expression, the throw is a compile-time error).
  static constexpr int q_offset(std::string_view joint) { return tree.q_offset[detail::joint_named<Scene>(joint)]; }
  static constexpr int v_offset(std::string_view joint) { return tree.v_offset[detail::joint_named<Scene>(joint)]; }
  [[deprecated("flange: q_index is now q_offset (q_offset<\"name\">() is checked at compile time)")]]
  static constexpr int q_index(std::string_view joint) { return q_offset(joint); }

  /// The state x = (q, v): every joint's coordinates, then every joint's rates.
  static constexpr int n_state = n_q + n_v;
  using state_type = std::array<double, n_state>;

  /// A state of the wrong size is a compile-time error when its type fixes
  /// the size, and an exception naming both sizes when it does not
  /// (std::vector, Odeint's most common state): never an out-of-bounds read.
  template <class State>
  static void require_state_size(const State& x) {
    constexpr int n = detail::static_size<State>();
    static_assert(detail::report<(n >= 0 && n != n_state) ? 0 : -1, diagnostic::wrong_state_size,
                                 detail::type_list<diagnostic::state_size_given<n>, diagnostic::state_size_needed<n_state>>>());
    if constexpr (n < 0) {
      if (static_cast<std::size_t>(x.size()) != std::size_t(n_state)) [[unlikely]]
        wrong_state_size(static_cast<std::size_t>(x.size()));
    }
  }
  [[noreturn, gnu::cold, gnu::noinline]] static void wrong_state_size(std::size_t size) {
    throw error(detail::concat("flange: a state of size ", size, " was given, but the scene's state x = (q, v) has ",
                               n_state, " entries (", n_q, " joint coordinates and ", n_v, " rates)"));
  }

  // ---------------------------------------------------------- values
  /// From one argument per component, in order, forwarded: each component
  /// is moved or copied once, into its place (see make_scene below).
  template <class... A>
  explicit Scene(std::in_place_t, A&&... a) : components_(std::in_place, std::forward<A>(a)...) {}

  template <int I>
  [[nodiscard]] const auto& component() const {
    return detail::value_at<std::size_t(I)>(components_);
  }
  template <fixed_string Name>
  [[nodiscard]] const auto& get() const {
    constexpr int i = index_of(Name.view());
    static_assert(i >= 0, "flange: the scene has no component of this name");
    return component<i>();
  }

  /// The World's gravity.
  [[nodiscard]] Vec3d gravity() const { return component<topology.world < 0 ? 0 : topology.world>().g(); }
  static constexpr bool has_gravity = component_type<topology.world < 0 ? 0 : topology.world>::has_gravity;

 private:
  detail::indexed_values<std::index_sequence_for<Cs...>, Cs...> components_;
};

namespace detail {
/// The positions of the arguments that are connections (Connection) or
/// components (!Connection), in order.
template <bool Connection, class... Args>
constexpr auto positions() {
  return indices_of<std::array<bool, sizeof...(Args)>{(is_connection<Args>::value == Connection)...}>();
}
template <auto Positions, class Seq, class... Args>
struct pick_types;
template <auto Positions, std::size_t... I, class... Args>
struct pick_types<Positions, std::index_sequence<I...>, Args...> {
  using type = type_list<nth_t<Positions[I], Args...>...>;
};

/// Make<the Scene of these arguments>(std::in_place, its components...):
/// the arguments are sorted into components and connections by looking each
/// one up by position, not by recursing over the list or filtering a tuple,
/// which both instantiate something per argument that holds the rest of the
/// list (gigabytes of compiler memory for a scene of a few hundred
/// components). Each component is forwarded to its place, not passed on by
/// value from layer to layer: a large scene's set-up stays small code.
template <template <class> class Make, class... Args>
auto make_scene(Args&&... args) {
  static constexpr auto components = positions<false, std::remove_cvref_t<Args>...>();
  static constexpr auto connections = positions<true, std::remove_cvref_t<Args>...>();
  using connection_types = typename pick_types<connections, std::make_index_sequence<connections.size()>,
                                               std::remove_cvref_t<Args>...>::type;
  using component_types = typename pick_types<components, std::make_index_sequence<components.size()>,
                                              std::remove_cvref_t<Args>...>::type;
  const indexed_values<std::index_sequence_for<Args...>, Args&&...> all(std::in_place, std::forward<Args>(args)...);
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return Make<Scene<component_types, typename resolve_connections<component_types, connection_types>::type>>(
        std::in_place, std::forward<nth_t<components[I], Args...>>(value_at<components[I]>(all))...);
  }(std::make_index_sequence<components.size()>{});
}
}  // namespace detail

/// The structure of a scene from components and connections, in any order
/// (flange::scene(...) in simulate/system.hpp adds the dynamics on top).
template <class... Args>
auto compose(Args... args) {
  return detail::make_scene<std::type_identity_t>(std::move(args)...);
}

}  // namespace flange
