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
  for (int f = 0; f < NF; ++f) {
    auto& k = sol.frames[f];
    detail::frame_pose_and_velocity(scene, lk, f, k);
    const int s = topo.set_of[f];
    const int l = tree.set_link[s];
    const auto& L = lk[l];
    const Vec3<T> p = scene.model().set_offset[s].template cast<T>();
    const Mat3<T> Rs = scene.model().set_rotation[s].template cast<T>();
    k.wd = Rs * wd[l];
    k.a = detail::point_acceleration(L, p, wd[l], a[l]) + g;  // a carries −g
  }

  // Flows of bodies and force elements, from their own equations.
  for (auto& c : sol.cut) c = {Vec3<T>::Zero(), Vec3<T>::Zero()};
  detail::for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int fb = tab.frame_base[decltype(i)::value];
    if constexpr (C::kind == role::body) sol.cut[fb] = c.flows(sol.frames[fb], g);
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
  // Edges (joints and rigid components) from the leaves inward.
  auto others_in_set = [&](int s, int except) FLANGE_INLINE_LAMBDA {
    wrench<T> w{Vec3<T>::Zero(), Vec3<T>::Zero()};
    for (int f = 0; f < NF; ++f)
      if (topo.set_of[f] == s && f != except) {
        w.f += sol.cut[f].f;
        w.n += sol.cut[f].n;
      }
    return w;
  };
  for (int i = tree.n_tree_sets - 1; i >= 1; --i) {
    const int s = tree.set_order[i];
    const bool root = tree.set_parent[s] < 0;
    const int e = root ? tree.link_joint[tree.set_link[s]] : tree.set_edge[s];
    const int dir = root ? tree.link_dir[tree.set_link[s]] : tree.set_edge_dir[s];
    const int child = tab.frame_base[e] + (dir > 0 ? 1 : 0), parent = tab.frame_base[e] + (dir > 0 ? 0 : 1);
    const wrench<T> o = others_in_set(s, child);
    sol.cut[child] = {-o.f, -o.n};
    detail::visit_component(scene, e, [&](const auto& c) FLANGE_INLINE_LAMBDA {
      using C = std::remove_cvref_t<decltype(c)>;
      if constexpr (C::kind == role::joint || C::kind == role::rigid) {
        const pose<T> x = [&]() FLANGE_INLINE_LAMBDA {
          if constexpr (C::kind == role::joint) return relative_pose_of(c, sol.q.data() + tree.q_offset[e]);
          else return c.template relative_pose<T>();
        }();
        if constexpr (carries_body<C>) {
          // A rigid edge with mass: its body's wrench at frame_a joins frame_a's flows.
          const wrench<T> body = c.flows(sol.frames[tab.frame_base[e]], g);
          if (dir > 0) {
            const wrench<T> a = flows_a_from_b(x, sol.cut[child]);
            sol.cut[parent] = {a.f + body.f, a.n + body.n};
          } else {
            sol.cut[parent] = flows_b_from_a(x, wrench<T>{sol.cut[child].f - body.f, sol.cut[child].n - body.n});
          }
        } else {
          sol.cut[parent] = dir > 0 ? flows_a_from_b(x, sol.cut[child]) : flows_b_from_a(x, sol.cut[child]);
        }
      }
    });
  }
  {
    const int wf = tab.frame_base[topo.world];
    const wrench<T> o = others_in_set(topo.set_of[wf], wf);
    sol.cut[wf] = {-o.f, -o.n};
  }

  // The flattened DAE vector.
  sol.y.setZero();
  sol.yd.setZero();
  for (int f = 0; f < NF; ++f) {
    const auto& k = sol.frames[f];
    sol.y.template segment<3>(S::frame_offset(f, 0)) = k.r;
    Eigen::Map<Mat3<T>>(sol.y.data() + S::frame_offset(f, 1)) = k.R;
    sol.y.template segment<3>(S::frame_offset(f, 2)) = sol.cut[f].f;
    sol.y.template segment<3>(S::frame_offset(f, 3)) = sol.cut[f].n;
    sol.yd.template segment<3>(S::frame_offset(f, 0)) = k.v;
    Eigen::Map<Mat3<T>>(sol.yd.data() + S::frame_offset(f, 1)) = -tilde<T>(k.w) * k.R;
  }
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
        sol.y.template segment<3>(o) = value;
        sol.yd.template segment<3>(o) = rate;
      } else {
        Eigen::Map<Mat3<T>>(sol.y.data() + o) = value;
        Eigen::Map<Mat3<T>>(sol.yd.data() + o) = rate;
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
      const Mat3<T> R = b.R * a.R.transpose();
      const Vec3<T> p = a.R * (b.r - a.r);
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
