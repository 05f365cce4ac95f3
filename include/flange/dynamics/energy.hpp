// A scene's energy at a state, from positions and velocities alone: every
// body's kinetic energy, gravity's potential and the springs' (joint springs
// and force elements with a potential). No dynamics runs, so it is cheap to
// instantiate for dual numbers: the mass matrix read off the kinetic energy
// (energy_mass_matrix.hpp) and the power balance of the tests differentiate
// it, where differentiating recover() would also differentiate the whole
// forward dynamics (and compile it once more for each dual type).
//
//   const auto e = flange::energy(scene, t, x);   // e.kinetic, e.potential(), e.total()
//
// recover() (recover.hpp) fills its frames and its energies with the same
// two functions, so the two cannot disagree.
#pragma once
#include <array>
#include <type_traits>

#include "flange/core/frame_kinematics.hpp"
#include "flange/detail/inline.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/dynamics/kinematics.hpp"
#include "flange/scene/named_state.hpp"

namespace flange {

/// The energy of a scene at a state, by kind.
template <class T>
struct energy_terms {
  T kinetic{};            ///< kinetic energy of every body
  T gravity_potential{};  ///< −Σ m·g·r_CM
  T elastic_potential{};  ///< every spring's: line springs and joint springs

  [[nodiscard]] T potential() const { return gravity_potential + elastic_potential; }
  [[nodiscard]] T total() const { return kinetic + potential(); }
};

namespace detail {

/// Every frame's pose and velocity (r, R, v, ω) from its link's: a frame
/// sits at its connection set's constant pose in its link (set_of: each
/// frame's set; set_link: each set's link; set_offset, set_rotation: the
/// set's place in its link). With wd and a (each link's ω̇ and r̈ in link
/// coordinates, a carrying −g), also the frames' accelerations (ω̇, r̈);
/// else those are left unset. Scene-independent: one copy at double for
/// every scene (FLANGE_COMMON).
template <class T>
void place_frames(int n_frames, const int* set_of, const int* set_link, const Vec3d* set_offset,
                  const Mat3d* set_rotation, const link_pose<T>* links, const Vec3<T>* wd, const Vec3<T>* a,
                  const Vec3<T>& g, frame_kinematics<T>* frames) {
  for (int f = 0; f < n_frames; ++f) {
    const int s = set_of[f], l = set_link[s];
    const link_pose<T>& L = links[l];
    frame_kinematics<T>& k = frames[f];
    const Vec3<T> p = set_offset[s].template cast<T>();
    const Mat3<T> Rs = set_rotation[s].template cast<T>();
    k.R = Rs * L.R;
    k.w = Rs * L.w;
    k.r = L.r + L.R.transpose() * p;
    const Vec3<T> wp = L.w.cross(p);
    k.v = L.v + L.R.transpose() * wp;
    if (wd) {
      k.wd = Rs * wd[l];
      k.a = L.R.transpose() * (a[l] + wd[l].cross(p) + L.w.cross(wp)) + g;  // a carries −g
    }
  }
}
FLANGE_COMMON(void place_frames<double>(int, const int*, const int*, const Vec3d*, const Mat3d*,
                                        const link_pose<double>*, const Vec3d*, const Vec3d*, const Vec3d&,
                                        frame_kinematics<double>*))

/// place_frames for a scene's frames, from its links' poses (and, with wd
/// and a, their accelerations).
template <class S, class T>
FLANGE_INLINE void place_scene_frames(const S& scene, const std::array<link_pose<T>, S::tree.n_links>& links,
                                      const Vec3<T>* wd, const Vec3<T>* a, const Vec3<T>& g,
                                      frame_kinematics<T>* frames) {
  place_frames<T>(S::n_frames, S::topology.set_of.data(), S::tree.set_link.data(), scene.model().set_offset.data(),
                  scene.model().set_rotation.data(), links.data(), wd, a, g, frames);
}

/// A body's kinetic energy and gravity's potential (m, r_CM and J about the
/// centre of mass in frame_a, whose motion is k), added to e.
template <class T>
void add_body_energy(const T& m, const Vec3<T>& cm, const Mat3<T>& J, const frame_kinematics<T>& k,
                     const Vec3<T>& g, energy_terms<T>& e) {
  const Vec3<T> vcm = k.v + k.R.transpose() * k.w.cross(cm);
  e.kinetic += T(0.5) * m * vcm.squaredNorm() + T(0.5) * k.w.dot(J * k.w);
  e.gravity_potential -= m * g.dot(k.r + k.R.transpose() * cm);
}
FLANGE_COMMON(void add_body_energy<double>(const double&, const Vec3d&, const Mat3d&,
                                           const frame_kinematics<double>&, const Vec3d&, energy_terms<double>&))

/// The energies of the scene whose frames have the poses and velocities in
/// frames (by global frame index), at joint state js (q: the coordinates).
template <class S, class T, class JS>
energy_terms<T> energy_of(const S& scene, const T& t, const JS& js, const T* q, const frame_kinematics<T>* frames) {
  constexpr auto& tree = S::tree;
  const Vec3<T> g = scene.gravity().template cast<T>();
  energy_terms<T> e;
  for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
    using C = std::remove_cvref_t<decltype(c)>;
    constexpr int I = decltype(i)::value;
    constexpr int fb = S::table.frame_base[I];
    if constexpr (C::kind == role::joint && tree.cut_of[I] < 0) {
      if constexpr (requires { c.elastic_energy(q); }) e.elastic_potential += c.elastic_energy(q + tree.q_offset[I]);
    }
    if constexpr (requires { c.potential_energy(t, js, frames); })
      e.elastic_potential += c.potential_energy(t, js, frames + fb);
    // (cast<double>() of a double vector is the vector itself, no copy)
    if constexpr (carries_body<C>)
      add_body_energy<T>(T(c.m()), c.r_cm().template cast<T>(), c.J().template cast<T>(), frames[fb], g, e);
  });
  return e;
}

/// A state's coordinates, rates, and every frame's pose and velocity: the
/// pose pass alone (no dynamics), for energy() and momentum().
template <class S, class T>
struct frames_at_state {
  std::array<T, S::n_q> q;
  std::array<T, S::n_v> v;
  std::array<frame_kinematics<T>, S::n_frames> frames;
  template <class State>
  frames_at_state(const S& scene, const State& x) {
    S::require_state_size(x);
    for (int i = 0; i < S::n_q; ++i) q[i] = x[i];
    for (int i = 0; i < S::n_v; ++i) v[i] = x[S::n_q + i];
    const auto motions = link_motions<spatial_algebra, T, true>(scene, q.data());
    place_scene_frames<S, T>(scene, link_poses<S>(motions, v.data()), nullptr, nullptr, Vec3<T>::Zero(),
                             frames.data());
  }
};

}  // namespace detail

/// The energy at time t and state x = (q, v): the pose pass and each body's
/// velocity, nothing more (recover() gives the same numbers with everything
/// else).
template <class S, class T = double, class State>
  requires(!std::is_integral_v<T>)
[[nodiscard]] energy_terms<T> energy(const S& scene, const T& t, const State& x) {
  const detail::frames_at_state<S, T> k(scene, x);
  return detail::energy_of(scene, t, state_view(scene, k.q.data(), k.v.data()), k.q.data(), k.frames.data());
}

/// energy(scene, 0, x): an integral time is a time in seconds.
template <class S, class I, class State>
  requires std::is_integral_v<I>
[[nodiscard]] energy_terms<double> energy(const S& scene, I t, const State& x) {
  return energy(scene, double(t), x);
}

}  // namespace flange
