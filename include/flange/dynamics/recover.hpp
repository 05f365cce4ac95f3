// Everything else, on demand: from (t, x) recover every variable of the DAE
// (every frame's r, R, F, M and every component internal, with the time
// derivatives the equations use), the frames' velocities and accelerations,
// and the energy (kinetic, gravity's potential and the springs').
//
// The residual evaluated on the recovered variables is ≈ 0: that is flange's
// main self-check, since the residual comes from the components' equations
// and the recovered values from the recursive algorithms.
//
// Cut forces are found from the leaves inward: in each connection set the
// flows sum to zero, so the flow at a joint's child-side frame is minus the sum
// of the others; the joint's own equations then give its parent-side flow.
#pragma once
#include <array>
#include <string_view>

#include "flange/components/frame_kinematics.hpp"
#include "flange/dynamics/newton_euler.hpp"
#include "flange/equations/residual.hpp"

namespace flange {

template <class S, class T>
struct dae_solution {
  T t{};
  dae_vector<S, T> y, yd;  ///< every DAE variable, and the derivatives the equations use
  std::array<T, S::n_q> q{}, qd{}, qdd{};
  std::array<frame_kinematics<T>, S::n_frames> frames;  ///< by global frame index
  std::array<wrench<T>, S::n_frames> cut;               ///< F and M at each frame (frame coordinates)
  T kinetic{};            ///< kinetic energy of every body
  T gravity_potential{};  ///< −Σ m·g·r_CM
  T elastic_potential{};  ///< every spring's: line springs and joint springs

  [[nodiscard]] T potential() const { return gravity_potential + elastic_potential; }
  [[nodiscard]] T energy() const { return kinetic + potential(); }
  /// The frame named "component.frame".
  [[nodiscard]] const frame_kinematics<T>& frame(std::string_view name) const { return frames[index(name)]; }
  /// The cut force and torque at the frame named "component.frame".
  [[nodiscard]] const wrench<T>& cut_at(std::string_view name) const { return cut[index(name)]; }

 private:
  static int index(std::string_view name) {
    const int f = S::frame_index(name);
    if (f < 0) throw error(detail::concat("flange: the scene has no frame \"", name, "\""));
    return f;
  }
};

template <class S, class T = double, class State>
[[nodiscard]] dae_solution<S, T> recover(const S& scene, const T& t, const State& x) {
  constexpr int N = S::n_q, NL = S::tree.n_links, NF = S::n_frames;
  constexpr auto& tree = S::tree;
  constexpr auto& topo = S::topology;
  constexpr auto& tab = S::table;
  S::require_state_size(x);
  dae_solution<S, T> sol;
  sol.t = t;
  for (int i = 0; i < N; ++i) {
    sol.q[i] = x[i];
    sol.qd[i] = x[N + i];
  }
  accelerations_newton_euler(scene, t, sol.q.data(), sol.qd.data(), sol.qdd.data());
  const joint_state<T> js{sol.q.data(), sol.qd.data(), N};
  const Vec3<T> g = scene.gravity().template cast<T>();

  // Link motion, physical (no gravity trick): R, r, ω, ṙ, ω̇, r̈.
  std::array<frame_kinematics<T>, NL> lk;
  for (auto& k : lk) {
    k.r = k.v = k.w = k.a = k.wd = Vec3<T>::Zero();
    k.R = Mat3<T>::Identity();
  }
  const auto xf = detail::joint_transforms(scene, sol.q.data());
  detail::for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = detail::link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& xj = std::get<L - 1>(xf);
    const auto& P = lk[LI::parent];
    auto& c = lk[L];
    const T qd = sol.qd[LI::q], qdd = sol.qdd[LI::q];
    const Vec3<T> p = scene.model().set_offset[LI::parent_set].template cast<T>() + xj.p();
    const Vec3<T> pd = XF::translates ? xj.axis(qd) : Vec3<T>::Zero();
    const Vec3<T> pdd = XF::translates ? xj.axis(qdd) : Vec3<T>::Zero();
    const Mat3<T> E = xj.matrix();
    c.R = E * P.R;
    c.r = P.r + P.R.transpose() * p;
    c.v = P.v + P.R.transpose() * (P.w.cross(p) + pd);
    c.a = P.a + P.R.transpose() * (P.wd.cross(p) + P.w.cross(P.w.cross(p)) + T(2) * P.w.cross(pd) + pdd);
    c.w = E * P.w;
    c.wd = E * P.wd;
    if constexpr (XF::rotates) {
      c.w += xj.axis(qd);
      c.wd += xj.axis(qdd) + c.w.cross(xj.axis(qd));
    }
  });

  // Frames: a frame sits at its set's constant offset p in its link.
  for (int f = 0; f < NF; ++f) {
    const int s = topo.set_of[f];
    const auto& L = lk[tree.set_link[s]];
    const Vec3<T> p = scene.model().set_offset[s].template cast<T>();
    auto& k = sol.frames[f];
    k.R = L.R;
    k.w = L.w;
    k.wd = L.wd;
    k.r = L.r + L.R.transpose() * p;
    k.v = L.v + L.R.transpose() * L.w.cross(p);
    k.a = L.a + L.R.transpose() * (L.wd.cross(p) + L.w.cross(L.w.cross(p)));
  }

  // Flows of bodies and force elements, from their own equations.
  for (auto& c : sol.cut) c = {Vec3<T>::Zero(), Vec3<T>::Zero()};
  detail::for_each_component(scene, [&](auto i, const auto& c) {
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
  // Edges from the leaves inward.
  auto others_in_set = [&](int s, int except) {
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
    detail::visit_component(scene, e, [&](const auto& c) {
      using C = std::remove_cvref_t<decltype(c)>;
      if constexpr (C::kind == role::joint || C::kind == role::rigid) {
        T q{0};
        if constexpr (C::kind == role::joint) q = sol.q[tree.q_index[e]];
        sol.cut[parent] = dir > 0 ? c.flows_a_from_b(sol.cut[child], q) : c.flows_b_from_a(sol.cut[child], q);
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
  sol.kinetic = sol.gravity_potential = sol.elastic_potential = T(0);
  detail::for_each_component(scene, [&](auto i, const auto& c) {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int I = decltype(i)::value;
    constexpr int nf = int(C::frames.size());
    auto at = [&](int slot) { return S::template slot_offset<I>(slot); };
    if constexpr (C::kind == role::joint) {
      const int qi = tree.q_index[I];
      sol.y(at(4 * nf)) = sol.q[qi];
      sol.yd(at(4 * nf)) = sol.qd[qi];
      sol.elastic_potential += c.elastic_energy(sol.q[qi]);
      if constexpr (C::type == joint_type::revolute) {
        const Mat3<T> Rrel = c.relative_rotation(sol.q[qi]);
        Eigen::Map<Mat3<T>>(sol.y.data() + at(4 * nf + 1)) = Rrel;
        Eigen::Map<Mat3<T>>(sol.yd.data() + at(4 * nf + 1)) =
            -tilde<T>(c.n().template cast<T>() * sol.qd[qi]) * Rrel;
      }
    }
    if constexpr (requires { c.internal_values(t, js, &sol.frames[0]); }) {
      const auto iv = c.internal_values(t, js, &sol.frames[tab.frame_base[I]]);
      for (int i = 0; i < int(iv.size()); ++i) {
        sol.y(at(4 * nf + i)) = iv[i].first;
        sol.yd(at(4 * nf + i)) = iv[i].second;
      }
    }
    if constexpr (requires { c.potential_energy(t, js, &sol.frames[0]); })
      sol.elastic_potential += c.potential_energy(t, js, &sol.frames[tab.frame_base[I]]);
    if constexpr (C::kind == role::body) {
      const auto& k = sol.frames[tab.frame_base[I]];
      sol.y.template segment<3>(at(4)) = k.v;
      sol.y.template segment<3>(at(5)) = k.w;
      sol.yd.template segment<3>(at(4)) = k.a;
      sol.yd.template segment<3>(at(5)) = k.wd;
      const Vec3<T> cm = c.r_cm().template cast<T>();
      const Vec3<T> vcm = k.v + k.R.transpose() * k.w.cross(cm);
      const T m = T(c.m());
      sol.kinetic += T(0.5) * m * vcm.squaredNorm() + T(0.5) * k.w.dot(c.J().template cast<T>() * k.w);
      sol.gravity_potential -= m * g.dot(k.r + k.R.transpose() * cm);
    }
  });
  return sol;
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
