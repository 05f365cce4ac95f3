// Everything else, on demand: from (t, x) recover every variable of the DAE
// (every frame's r, R, F, M and every component internal, with the time
// derivatives the equations use), the frames' velocities and accelerations,
// and the energy (kinetic, gravity's potential and the springs').
//
// The residual evaluated on the recovered variables is ≈ 0: that is flange's
// main self-check, since the residual comes from the components' equations
// and the recovered values from the recursive algorithms.
//
// The link kinematics come from the same passes the dynamics use
// (kinematics.hpp): the pose pass for R, r, ṙ and ω, and the Newton–Euler
// forward step at the accelerations v̇ for ω̇ and r̈. Cut forces are found from
// the leaves inward: in each connection set the flows sum to zero, so the flow
// at an edge's child-side frame is minus the sum of the others; the edge's
// force and moment balance (core/joint.hpp) then gives its parent-side flow.
#pragma once
#include "flange/scene/named_state.hpp"
#include "flange/detail/inline.hpp"
#include <array>
#include <string_view>
#include <tuple>
#include <utility>

#include "flange/core/frame_kinematics.hpp"
#include "flange/dynamics/algorithm.hpp"
#include "flange/dynamics/energy.hpp"
#include "flange/dynamics/kinematics.hpp"
#include "flange/equations/residual.hpp"
#include "flange/scene/joint_check.hpp"

namespace flange {

namespace diagnostic {
template <class Component, class Closest>
struct no_component_of_this_name {
  static_assert(always_false<Component>,
                "flange: internal<\"component\", \"variable\">(): the scene has no component of this name (the "
                "first template argument); did you mean the second?");
};
template <class Component, class Variable, class Closest>
struct no_internal_of_this_name {
  static_assert(always_false<Component>,
                "flange: internal<\"component\", \"variable\">(): this component has no internal variable of this "
                "name (the second template argument); did you mean the third? Its header and print_equations list "
                "its variables");
};
}  // namespace diagnostic

namespace detail {
/// The names of component C's internal variables, Greek letters in ASCII
/// (as a suggestion prints them readably).
template <class C>
inline constexpr auto internal_ascii = [] {
  std::array<ascii_name, C::internals.size()> a{};
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = ascii_name(C::internals[i].name);
  return a;
}();
template <class C>
inline constexpr auto internal_names = [] {
  std::array<std::string_view, C::internals.size()> a{};
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = internal_ascii<C>[i].view();
  return a;
}();
}  // namespace detail

namespace detail {
/// One step of the sweep of cut forces from the leaves inward: in connection
/// set `set` the flows at every frame but `child` are known, so the set's
/// balance gives child's; the edge (a joint or a rigid component) from child
/// to `parent`, its other frame, then gives parent's by its force and moment
/// balance.
struct cut_step {
  int set, child, parent;
};
/// A scene's steps, leaves first, and last the World's set (child: the
/// World's frame, parent: none).
template <class S>
inline constexpr auto cut_steps = [] {
  constexpr auto& tree = S::tree;
  constexpr auto& tab = S::table;
  std::array<cut_step, S::tree.n_tree_sets> out{};
  int k = 0;
  for (int i = tree.n_tree_sets - 1; i >= 1; --i) {
    const int s = tree.set_order[i];
    const bool root = tree.set_parent[s] < 0;
    const int e = root ? tree.link_joint[tree.set_link[s]] : tree.set_edge[s];
    const int dir = root ? tree.link_dir[tree.set_link[s]] : tree.set_edge_dir[s];
    out[k++] = {s, tab.frame_base[e] + (dir > 0 ? 1 : 0), tab.frame_base[e] + (dir > 0 ? 0 : 1)};
  }
  const int wf = tab.frame_base[S::topology.world];
  out[k] = {S::topology.set_of[wf], wf, -1};
  return out;
}();

/// Frame b's pose relative to frame a (core/joint.hpp's pose) from the two
/// frames' world poses.
template <class T>
pose<T> pose_between(const frame_kinematics<T>& a, const frame_kinematics<T>& b) {
  return {b.R * a.R.transpose(), a.R * (b.r - a.r)};
}

/// The cut forces of every tree edge's frames, from the flows already in cut
/// (bodies, force elements, cut joints; zero elsewhere) by the steps. An
/// edge's relative pose comes from its frames' poses; body holds, at frame_a
/// of an edge that carries a body, that body's flows (zero elsewhere).
/// Scene-independent: one copy at double for every scene (FLANGE_COMMON).
template <class T>
void sweep_cut_forces(const cut_step* steps, int n_steps, const int* set_of, int n_frames,
                      const frame_kinematics<T>* frames, const wrench<T>* body, wrench<T>* cut) {
  for (int i = 0; i < n_steps; ++i) {
    const cut_step st = steps[i];
    wrench<T> o{Vec3<T>::Zero(), Vec3<T>::Zero()};
    for (int f = 0; f < n_frames; ++f)
      if (set_of[f] == st.set && f != st.child) {
        o.f += cut[f].f;
        o.n += cut[f].n;
      }
    cut[st.child] = {-o.f, -o.n};
    if (st.parent < 0) continue;
    const bool child_is_b = st.child > st.parent;
    const frame_kinematics<T>& fa = frames[child_is_b ? st.parent : st.child];
    const frame_kinematics<T>& fb = frames[child_is_b ? st.child : st.parent];
    const pose<T> x = pose_between(fa, fb);
    const wrench<T>& B = body[child_is_b ? st.parent : st.child];
    if (child_is_b) {
      const wrench<T> a = flows_a_from_b(x, cut[st.child]);
      cut[st.parent] = {a.f + B.f, a.n + B.n};
    } else {
      cut[st.parent] = flows_b_from_a(x, wrench<T>{cut[st.child].f - B.f, cut[st.child].n - B.n});
    }
  }
}
FLANGE_COMMON(void sweep_cut_forces<double>(const cut_step*, int, const int*, int, const frame_kinematics<double>*,
                                            const wrench<double>*, wrench<double>*))

/// The frames' variables into the flattened DAE vectors y and ẏ (zeroed
/// first): frame f's r, R, F and M at stride·f + offset[0 … 3], and ṙ and Ṙ.
template <class T>
void flatten_frames(int n_frames, int stride, const int* offset, const frame_kinematics<T>* frames,
                    const wrench<T>* cut, T* y, T* yd, int n) {
  for (int i = 0; i < n; ++i) y[i] = yd[i] = T(0);
  for (int f = 0; f < n_frames; ++f) {
    const frame_kinematics<T>& k = frames[f];
    T* o = y + stride * f;
    T* od = yd + stride * f;
    Eigen::Map<Vec3<T>>(o + offset[0]) = k.r;
    Eigen::Map<Mat3<T>>(o + offset[1]) = k.R;
    Eigen::Map<Vec3<T>>(o + offset[2]) = cut[f].f;
    Eigen::Map<Vec3<T>>(o + offset[3]) = cut[f].n;
    Eigen::Map<Vec3<T>>(od + offset[0]) = k.v;
    Eigen::Map<Mat3<T>>(od + offset[1]) = -tilde<T>(k.w) * k.R;
  }
}
FLANGE_COMMON(void flatten_frames<double>(int, int, const int*, const frame_kinematics<double>*,
                                          const wrench<double>*, double*, double*, int))

/// An internal variable's value and rate into y and ẏ at y and yd: a
/// 3-vector, or a rotation (column-major, as the DAE vector holds it).
template <class T>
void put_vector(T* y, T* yd, const Vec3<T>& value, const Vec3<T>& rate) {
  for (int i = 0; i < 3; ++i) {
    y[i] = value[i];
    yd[i] = rate[i];
  }
}
FLANGE_COMMON(void put_vector<double>(double*, double*, const Vec3d&, const Vec3d&))
template <class T>
void put_matrix(T* y, T* yd, const Mat3<T>& value, const Mat3<T>& rate) {
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      y[3 * j + i] = value(i, j);
      yd[3 * j + i] = rate(i, j);
    }
}
FLANGE_COMMON(void put_matrix<double>(double*, double*, const Mat3d&, const Mat3d&))
}  // namespace detail

/// Every variable of the DAE at one instant, with the energies
/// (energy_terms: kinetic, gravity_potential, elastic_potential).
template <class S, class T>
struct dae_solution : energy_terms<T> {
  T t{};
  dae_vector<S, T> y, yd;  ///< every DAE variable, and the derivatives the equations use
  std::array<T, S::n_q> q{};                            ///< joint coordinates
  std::array<T, S::n_v> v{}, vdot{};                    ///< joint rates and their derivatives
  std::array<frame_kinematics<T>, S::n_frames> frames;  ///< by global frame index
  std::array<wrench<T>, S::n_frames> cut;               ///< F and M at each frame (frame coordinates)
  /// Kinetic and potential energy together (energy_terms::total()).
  [[nodiscard]] T energy() const { return this->total(); }
  /// The frame named "component.frame". On a temporary solution
  /// (recover(…).frame(…)) a copy, so that `const auto& f = recover(…).frame(…)`
  /// does not dangle (AddressSanitizer found one in a test).
  [[nodiscard]] const frame_kinematics<T>& frame(std::string_view name) const& { return frames[index(name)]; }
  [[nodiscard]] frame_kinematics<T> frame(std::string_view name) && { return frames[index(name)]; }
  /// The cut force and torque at the frame named "component.frame" (a copy on a temporary).
  [[nodiscard]] const wrench<T>& cut_at(std::string_view name) const& { return cut[index(name)]; }
  [[nodiscard]] wrench<T> cut_at(std::string_view name) && { return cut[index(name)]; }
  /// A component's internal variable by name, found at compile time:
  /// sol.internal<"buffer", "f">() is a SpringDamper's tension,
  /// sol.internal<"joint", "R_rel">() a joint's relative rotation. A T, a
  /// Vec3<T> or a Mat3<T>, by the variable's kind; a misspelt name is one
  /// static_assert naming it.
  template <fixed_string Component, fixed_string Variable>
  [[nodiscard]] auto internal() const {
    return read<Component, Variable>(y);
  }
  /// Its time derivative, where the equations use one (else 0).
  template <fixed_string Component, fixed_string Variable>
  [[nodiscard]] auto internal_rate() const {
    return read<Component, Variable>(yd);
  }

 private:
  template <fixed_string Component, fixed_string Variable>
  static constexpr int internal_slot() {
    constexpr int c = S::index_of(Component.view());
    if constexpr (c < 0) {
      (void)sizeof(diagnostic::no_component_of_this_name<diagnostic::member<Component>,
                                                          diagnostic::suggest<S::table.names, Component>>);
      return -1;
    } else {
      using C = typename S::template component_type<c>;
      constexpr int k = [] {
        for (int i = 0; i < int(C::internals.size()); ++i)
          if (detail::same_name(C::internals[i].name, Variable.view())) return i;
        return -1;
      }();
      if constexpr (k < 0) {
        (void)sizeof(diagnostic::no_internal_of_this_name<diagnostic::member<Component>, diagnostic::member<Variable>,
                                                          diagnostic::suggest<detail::internal_names<C>, Variable>>);
        return -1;
      } else {
        return S::template slot_offset<c>(4 * int(C::frames.size()) + k);
      }
    }
  }
  template <fixed_string Component, fixed_string Variable>
  static constexpr expr::var_kind internal_kind() {
    constexpr int c = S::index_of(Component.view());
    if constexpr (c < 0) {
      return expr::var_kind::scalar;
    } else {
      using C = typename S::template component_type<c>;
      for (const auto& d : C::internals)
        if (detail::same_name(d.name, Variable.view())) return d.kind;
      return expr::var_kind::scalar;
    }
  }
  template <fixed_string Component, fixed_string Variable, class Y>
  static auto read(const Y& v) {
    constexpr int o = internal_slot<Component, Variable>();
    constexpr auto kind = internal_kind<Component, Variable>();
    if constexpr (o < 0) return T(0);
    else if constexpr (kind == expr::var_kind::scalar) return T(v(o));
    else if constexpr (kind == expr::var_kind::vec) return Vec3<T>(v.template segment<3>(o));
    else return Mat3<T>(Eigen::Map<const Mat3<T>>(v.data() + o));
  }

  static int index(std::string_view name) {
    const int f = S::frame_index(name);
    if (f < 0) throw error(detail::concat("flange: the scene has no frame \"", name, "\""));
    return f;
  }
};

/// internal<"buffer", "f">(sol): sol.internal<"buffer", "f">() as a free
/// function, for generic lambdas (where the member needs `template`).
template <fixed_string Component, fixed_string Variable, class S, class T>
[[nodiscard]] auto internal(const dae_solution<S, T>& sol) {
  return sol.template internal<Component, Variable>();
}
/// internal_rate<"buffer", "f">(sol): its time derivative.
template <fixed_string Component, fixed_string Variable, class S, class T>
[[nodiscard]] auto internal_rate(const dae_solution<S, T>& sol) {
  return sol.template internal_rate<Component, Variable>();
}

template <class S, class T = double, class State>
  requires(!std::is_integral_v<T>)
[[nodiscard]] dae_solution<S, T> recover(const S& scene, const T& t, const State& x) {
  constexpr int NL = S::tree.n_links, NF = S::n_frames;
  constexpr auto& tree = S::tree;
  constexpr auto& topo = S::topology;
  constexpr auto& tab = S::table;
  S::require_state_size(x);
  dae_solution<S, T> sol;
  sol.t = t;
  for (int i = 0; i < S::n_q; ++i) sol.q[i] = x[i];
  for (int i = 0; i < S::n_v; ++i) sol.v[i] = x[S::n_q + i];
  std::array<T, detail::n_constraints<S>()> lambda{};
  if constexpr (detail::has_loops<S>)
    accelerations_and_constraint_forces(scene, t, sol.q.data(), sol.v.data(), sol.vdot.data(), lambda.data());
  else accelerations(scene, t, sol.q.data(), sol.v.data(), sol.vdot.data());
  const auto js = state_view(scene, sol.q.data(), sol.v.data());
  const Vec3<T> g = scene.gravity().template cast<T>();

  // Link motion, physical: R, r, ṙ, ω from the pose pass; ω̇ and r̈ from the
  // forward step at v̇ (whose a carries −g).
  const auto motions = detail::link_motions<spatial_algebra, T, true>(scene, sol.q.data());
  const auto lk = detail::link_poses<S>(motions, sol.v.data());
  std::array<Vec3<T>, NL> wd, a;
  detail::link_accelerations<S, T>(motions, sol.v.data(), sol.vdot.data(),
                                   detail::base_kinematics<spatial_algebra, T>(scene), wd, a);

  // Frames: a frame sits at its set's constant pose in its link (its pose
  // and velocity as energy() has them, energy.hpp).
  detail::place_scene_frames<S, T>(scene, lk, wd.data(), a.data(), g, sol.frames.data());

  // Flows of bodies and force elements, from their own equations.
  for (auto& c : sol.cut) c = {Vec3<T>::Zero(), Vec3<T>::Zero()};
  std::array<wrench<T>, NF> edge_body;  // a rigid edge's body's flows at its frame_a
  for (auto& w : edge_body) w = {Vec3<T>::Zero(), Vec3<T>::Zero()};
  detail::for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int fb = tab.frame_base[decltype(i)::value];
    if constexpr (C::kind == role::body) sol.cut[fb] = c.flows(sol.frames[fb], g);
    if constexpr ((C::kind == role::joint || C::kind == role::rigid) && carries_body<C>)
      edge_body[fb] = c.flows(sol.frames[fb], g);
    if constexpr (C::kind == role::force) {
      // The element's flows are minus what it exerts, in frame coordinates.
      constexpr int nf = int(C::frames.size());
      std::array<wrench<T>, nf> on;
      c.wrenches(t, js, &sol.frames[fb], on.data());
      for (int k = 0; k < nf; ++k) {
        const Mat3<T>& R = sol.frames[fb + k].R;
        sol.cut[fb + k] = {-(R * on[k].f), -(R * on[k].n)};
      }
    }
  });
  // Cut joints: the constraint forces λ act on their two frames, each row
  // with its coefficients on the frames' motions (dynamics/loops.hpp).
  if constexpr (detail::has_loops<S>) {
    const auto lt = detail::loop_kinematics<S>(scene, sol.q.data(), sol.v.data());
    detail::for_cuts<S>([&](auto k) FLANGE_INLINE_LAMBDA {
      using CI = detail::cut_info<S, decltype(k)::value>;
      wrench<T> on_a{Vec3<T>::Zero(), Vec3<T>::Zero()}, on_b = on_a;
      for (int i = detail::cut_row<S, decltype(k)::value>(); i < detail::cut_row<S, decltype(k)::value>() + CI::rows;
           ++i) {
        const auto& r = lt.rows[i];
        on_a.n += lambda[i] * r.wa;
        on_a.f += lambda[i] * r.va;
        on_b.n += lambda[i] * r.wb;
        on_b.f += lambda[i] * r.vb;
      }
      constexpr int fa = tab.frame_base[CI::joint];
      const Mat3<T>& Ra = sol.frames[fa].R;
      const Mat3<T>& Rb = sol.frames[fa + 1].R;
      sol.cut[fa] = {-(Ra * on_a.f), -(Ra * on_a.n)};
      sol.cut[fa + 1] = {-(Rb * on_b.f), -(Rb * on_b.n)};
    });
  }
  // Edges (joints and rigid components) from the leaves inward, then the
  // World's frame.
  constexpr auto& steps = detail::cut_steps<S>;
  detail::sweep_cut_forces<T>(steps.data(), int(steps.size()), topo.set_of.data(), NF, sol.frames.data(),
                              edge_body.data(), sol.cut.data());

  // The flattened DAE vector.
  detail::flatten_frames<T>(NF, frame_storage, frame_var_offset.data(), sol.frames.data(), sol.cut.data(),
                            sol.y.data(), sol.yd.data(), int(sol.y.size()));
  detail::for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int I = decltype(i)::value;
    constexpr int nf = int(C::frames.size());
    auto at = [&](int slot) FLANGE_INLINE_LAMBDA { return S::template slot_offset<I>(slot); };
    // An internal's value and rate into y and ẏ (a scalar, a 3-vector or a rotation).
    auto set = [&](int k, const auto& value, const auto& rate) FLANGE_INLINE_LAMBDA {
      using V = std::remove_cvref_t<decltype(value)>;
      const int o = at(4 * nf + k);
      if constexpr (std::is_same_v<V, T>) {
        sol.y(o) = value;
        sol.yd(o) = rate;
      } else if constexpr (V::SizeAtCompileTime == 3) {
        detail::put_vector<T>(sol.y.data() + o, sol.yd.data() + o, value, rate);
      } else {
        detail::put_matrix<T>(sol.y.data() + o, sol.yd.data() + o, value, rate);
      }
    };
    if constexpr (C::kind == role::joint && tree.cut_of[I] < 0) {
      const T* q = sol.q.data() + tree.q_offset[I];
      const T* v = sol.v.data() + tree.v_offset[I];
      c.write_internals(q, v, set);
    } else if constexpr (C::kind == role::joint) {
      // A cut joint: its coordinates from its frames, as it would have them.
      const auto& a = sol.frames[tab.frame_base[I]];
      const auto& b = sol.frames[tab.frame_base[I] + 1];
      // (Not a structured binding: clang 14 refuses one in the requires-expression below.)
      const pose<T> ab = detail::pose_between(a, b);
      const Mat3<T>& R = ab.R;
      const Vec3<T>& p = ab.p;
      const Vec3<T> w = a.R * (b.R.transpose() * b.w) - a.w;
      const Vec3<T> pd = a.R * (b.v - a.v) - a.w.cross(p);
      std::array<T, C::nq> q;
      std::array<T, C::nv> v;
      static_assert(requires { c.cut_state(R, p, w, pd, q.data(), v.data()); },
                    "flange: recover() needs cut_state() of a joint that closes a loop (core/joint.hpp)");
      c.cut_state(R, p, w, pd, q.data(), v.data());
      c.write_internals(q.data(), v.data(), set);
    }
    if constexpr (requires { c.internal_values(t, js, &sol.frames[0]); }) {
      // (value, rate) pairs: an array, or a tuple where the kinds differ.
      const auto iv = c.internal_values(t, js, &sol.frames[tab.frame_base[I]]);
      [&]<std::size_t... K>(std::index_sequence<K...>) FLANGE_INLINE_LAMBDA {
        (set(int(K), std::get<K>(iv).first, std::get<K>(iv).second), ...);
      }(std::make_index_sequence<std::tuple_size_v<std::remove_cvref_t<decltype(iv)>>>{});
    }
    if constexpr (carries_body<C>) {
      const auto& k = sol.frames[tab.frame_base[I]];
      set(0, k.v, k.a);   // v
      set(1, k.w, k.wd);  // ω
    }
  });
  static_cast<energy_terms<T>&>(sol) = detail::energy_of(scene, t, js, sol.q.data(), sol.frames.data());
  return sol;
}

/// recover(scene, 0, x): an integral time is a time in seconds.
template <class S, class I, class State>
  requires std::is_integral_v<I>
[[nodiscard]] dae_solution<S, double> recover(const S& scene, I t, const State& x) {
  return recover(scene, static_cast<double>(t), x);
}

/// max |F(t, y, ẏ)| over the rows, relative to max(1, max |y|, max |ẏ|): the
/// scaled residual of a recovered solution.
template <class S, class T>
[[nodiscard]] T scaled_residual(const S& scene, const dae_solution<S, T>& sol) {
  using std::max;
  const T scale = max({T(1), sol.y.cwiseAbs().maxCoeff(), sol.yd.cwiseAbs().maxCoeff()});
  return residual(scene, sol.t, sol.y, sol.yd).cwiseAbs().maxCoeff() / scale;
}

}  // namespace flange
