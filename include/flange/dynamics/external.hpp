// What force elements do to the links: the torques n_ext and forces f_ext
// they exert on each link, in link coordinates about the link origin.
//
// A Torque needs the link rotations only: its torque is carried into the
// links it acts on. Line forces (Spring, Damper, SpringDamper) and world loads
// (WorldForce, WorldTorque) need the frames' positions and velocities; for
// scenes with them only, a pose pass (kinematics.hpp) runs first and each
// element reports the wrench it exerts at its frames (wrenches()), or, for a
// Contact against a half-space at rest in the World (a ground, a wall), adds
// its loads in its link's coordinates directly (half_space_loads(): the
// half-space turned into the link, nothing turned back). A scene without
// force elements has none of this.
#pragma once
#include "flange/math/read_alone.hpp"
#include <array>
#include <vector>
#include <string>

#include "flange/detail/inline.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/dynamics/kinematics.hpp"
#include "flange/errors.hpp"

namespace flange::detail {

/// The connection set of component C's K-th frame, and whether the frame is
/// turned against its link (a FixedRotation or an axis frame on the way).
template <class S, int C, int K>
inline constexpr int frame_set = S::topology.set_of[S::table.frame_base[C] + K];
template <class S, int C, int K>
inline constexpr bool frame_turned = set_rotation_kind<S>(frame_set<S, C, K>) != -2;

/// The links a force element's frames sit on, frame by frame (0: the World's).
/// A one-frame element (WorldForce, WorldTorque) takes its reaction from the World.
template <class S, int C>
constexpr auto force_links() {
  using Comp = typename S::template component_type<C>;
  std::array<int, Comp::frames.size()> l{};
  for (int k = 0; k < int(Comp::frames.size()); ++k)
    l[k] = S::tree.set_link[S::topology.set_of[S::table.frame_base[C] + k]];
  return l;
}
/// Whether a force element acts between different links (or on one link, from the World).
template <class S, int C>
constexpr bool force_acts() {
  constexpr auto l = force_links<S, C>();
  if constexpr (l.size() == 1) return l[0] != 0;
  else return l[0] != l[1];
}
/// Whether force element type C's loads read the joint state (an input of
/// (t, x)) besides its frames' motions and the time: its optional member
/// reads_state, else assumed so.
template <class C>
constexpr bool element_reads_state() {
  if constexpr (requires { C::reads_state; }) return C::reads_state;
  else return true;
}

/// Whether any force element needs the frames' positions and velocities.
template <class S>
constexpr bool has_motion_forces() {
  return []<int... C>(std::integer_sequence<int, C...>) FLANGE_INLINE_LAMBDA {
    return (false || ... || [] {
      using Comp = typename S::template component_type<C>;
      if constexpr (Comp::kind == role::force) return Comp::needs_motion && force_acts<S, C>();
      else return false;
    }());
  }(std::make_integer_sequence<int, S::n_components>{});
}

/// Which links some element acts on: with a torque, and with a force.
/// (loaded_links: the first, as link_poses' Keep.)
template <class S>
struct load_flags {
  static constexpr int NL = S::tree.n_links;
  struct table {
    std::array<bool, NL> torque{}, force{};
  };
  static constexpr table value = [] {
    table t{};
    [&]<int... C>(std::integer_sequence<int, C...>) FLANGE_INLINE_LAMBDA {
      (
          [&]() FLANGE_INLINE_LAMBDA {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force) {
              if constexpr (force_acts<S, C>())
                for (int l : force_links<S, C>()) {
                  t.torque[l] = true;
                  if constexpr (Comp::exerts_force) t.force[l] = true;
                }
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    t.torque[0] = t.force[0] = false;  // the World takes what it is given
    return t;
  }();
};

/// The links some element acts on (link_poses' Keep).
template <class S>
struct loaded_links {
  static constexpr auto value = load_flags<S>::value.torque;
};

template <class S, class T>
using link_loads = std::array<Vec3<T>, S::tree.n_links>;

/// A vector in link L's coordinates from world coordinates, and back, through
/// the chain of link rotations (motions: a tuple from link_motions).
template <int L, class S, class M, class V>
auto world_to_link(const M& motions, const V& v) {
  if constexpr (L == 0) return v;
  else return rot(std::get<L - 1>(motions).E(), world_to_link<link_info<S, L>::parent, S>(motions, v));
}
template <int L, class S, class M, class V>
auto link_to_world(const M& motions, const V& v) {
  if constexpr (L == 0) return v;
  else return link_to_world<link_info<S, L>::parent, S>(motions, rot_t(std::get<L - 1>(motions).E(), v));
}

/// The frame of component C's k-th frame, from its link's world pose.
template <class S, int C, int K, class T>
FLANGE_INLINE frame_kinematics<T> frame_from_link(const S& scene, const link_pose<T, velocity_in::link>& L) {
  constexpr int set = frame_set<S, C, K>;
  constexpr bool on_world = force_links<S, C>()[K] == 0;
  constexpr bool turned = frame_turned<S, C, K>;
  const Vec3<T> p = scene.model().set_offset[set].template cast<T>();
  frame_kinematics<T> f;
  f.a = f.wd = Vec3<T>::Zero();
  if constexpr (on_world) {  // a frame on the World: at rest
    if constexpr (turned) f.R = scene.model().set_rotation[set].template cast<T>();
    else f.R.setIdentity();
    f.w.setZero();
    f.r = p;
    f.v.setZero();
  } else {
    if constexpr (turned) {
      const Mat3<T> Rs = scene.model().set_rotation[set].template cast<T>();
      f.R.noalias() = Rs * L.R;
      f.w.noalias() = Rs * L.w;
    } else {
      f.R = L.R;
      f.w = L.w;
    }
    f.r = point_position(L, p);
    f.v = point_velocity(L, p);
  }
  return f;
}

/// Whether force element C meets a half-space at rest in the World: a
/// Contact whose shape b is a half-space, its frame_b on the World.
template <class S, int C>
constexpr bool meets_resting_half_space() {
  using Comp = typename S::template component_type<C>;
  if constexpr (requires { Comp::against_half_space; }) return Comp::against_half_space && force_links<S, C>()[1] == 0;
  else return false;
}

/// What force element C (meets_resting_half_space) exerts on frame_a's link
/// L, added to its loads f, n: the half-space in world coordinates, turned
/// into the link's with its velocity.
template <class S, int C, class T>
FLANGE_INLINE void resting_half_space_loads(const S& scene, const link_pose<T, velocity_in::link>& L, Vec3<T>& f,
                                            Vec3<T>& n) {
  constexpr int set_a = frame_set<S, C, 0>, set_b = frame_set<S, C, 1>;
  const auto& c = scene.template component<C>();
  const auto& plane = c.geometry().b;
  Vec3d n_w = plane.n;  // {x : n_w·x ≤ o_w}, world coordinates
  if constexpr (frame_turned<S, C, 1>) n_w = scene.model().set_rotation[set_b].transpose() * plane.n;
  const double o_w = plane.offset + n_w.dot(scene.model().set_offset[set_b]);
  const auto meet = [&](const Vec3<T>& n_L, const T& h, const Vec3<T>& v, const Vec3<T>& w) FLANGE_INLINE_LAMBDA {
    c.template half_space_loads<frame_turned<S, C, 0>>(n_L, h, v, w, scene.model().set_offset[set_a],
                                                       scene.model().set_rotation[set_a], f, n);
  };
  if constexpr (S::tree.link_parent[force_links<S, C>()[0]] == 0) {
    // A link on the World: its pose was written entry by entry moments ago,
    // by the pose pass's first step, and a 16-byte load of two entries would
    // wait for both stores to reach the cache. Its r, v and ω are read a
    // scalar at a time and n_L is formed from scalars (math/read_alone.hpp).
    // (On deeper links, the quadruped's feet, the scalar reads measured no
    // faster and cost instructions.)
    const Vec3<T> r = flange::read_alone(L.r), v = flange::read_alone(L.v), w = flange::read_alone(L.w);
    Vec3<T> n_L;
    for (int i = 0; i < 3; ++i) n_L[i] = flange::read_alone(T(L.R(i, 0) * n_w[0] + L.R(i, 1) * n_w[1] + L.R(i, 2) * n_w[2]));
    meet(n_L, r[0] * n_w[0] + r[1] * n_w[1] + r[2] * n_w[2] - T(o_w), v, w);
  } else {
    meet(L.R * n_w.template cast<T>(), n_w.template cast<T>().dot(L.r) - T(o_w), L.v, L.w);
  }
}

/// The loads of the scene's force elements on each link. Only the links
/// load_flags mark are written. motions: the algorithm's (algebra A) link
/// motions; pose_motions: spatial motions with rotations, used when a pose
/// pass is needed (they may be the same tuple).
template <class A, class S, class T, class M, class PM>
FLANGE_INLINE void gather_external(const S& scene, const T& t, const state_of<T> auto& x, const M& motions, const PM& pose_motions,
                     link_loads<S, T>& n_ext, link_loads<S, T>& f_ext) {
  constexpr auto F = load_flags<S>::value;
  if constexpr (has_motion_forces<S>()) {
    // These sums start from −0, not +0: x + (−0) is x for every x, so the
    // compiler drops the first element's addition (x + (+0) is not x when x
    // is −0, so that one it must do), which stood in the way from a contact
    // force to the accelerations.
    for (int L = 0; L < S::tree.n_links; ++L) {
      if (F.torque[L]) n_ext[L].setConstant(T(-0.0));
      if (F.force[L]) f_ext[L].setConstant(T(-0.0));
    }
    const auto lk = link_poses<S, T, loaded_links<S>, velocity_in::link>(pose_motions, x.v_);
    [&]<int... C>(std::integer_sequence<int, C...>) FLANGE_INLINE_LAMBDA {
      (
          [&]() FLANGE_INLINE_LAMBDA {
            using Comp = typename S::template component_type<C>;
            if constexpr (meets_resting_half_space<S, C>()) {
              constexpr int l = force_links<S, C>()[0];
              resting_half_space_loads<S, C>(scene, lk[l], f_ext[l], n_ext[l]);
            } else if constexpr (Comp::kind == role::force && force_acts<S, C>()) {
              constexpr int nf = int(Comp::frames.size());
              constexpr auto links = force_links<S, C>();
              std::array<frame_kinematics<T>, nf> fk;
              std::array<Vec3<T>, nf> p;
              static_for<nf>([&](auto k) FLANGE_INLINE_LAMBDA {
                constexpr int K = decltype(k)::value;
                fk[K] = frame_from_link<S, C, K>(scene, lk[links[K]]);
                p[K] = scene.model().set_offset[frame_set<S, C, K>].template cast<T>();
              });
              std::array<wrench<T>, nf> on;
              scene.template component<C>().wrenches(t, x, fk.data(), on.data());
              for (int k = 0; k < nf; ++k) {
                const int l = links[k];
                if (l == 0) continue;
                if constexpr (Comp::exerts_force) {
                  const Vec3<T> f = lk[l].R * on[k].f;
                  f_ext[l] += f;
                  n_ext[l] += p[k].cross(f);
                }
                if constexpr (Comp::exerts_torque) n_ext[l] += lk[l].R * on[k].n;
              }
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
  } else {
    (void)pose_motions;
    for (int L = 0; L < S::tree.n_links; ++L) {
      if (F.torque[L]) n_ext[L].setZero();
      if (F.force[L]) f_ext[L].setZero();
    }
    [&]<int... C>(std::integer_sequence<int, C...>) FLANGE_INLINE_LAMBDA {
      (
          [&]() FLANGE_INLINE_LAMBDA {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force && force_acts<S, C>()) {
              constexpr auto links = force_links<S, C>();
              constexpr int la = links[0], lb = links[1];
              // A pure torque: M_ext (frame_a coordinates) acts on frame_b's
              // side, −M_ext on frame_a's; a frame turned against its link
              // (FixedRotation) first turns it into link coordinates.
              constexpr int set_a = frame_set<S, C, 0>;
              const auto Ra = set_rotation<A, T, S, set_a>(scene);
              const auto Mt = rot_t(Ra, angular<A, T>(scene.template component<C>().torque(t, x)));
              if constexpr (lb != 0) {
                if constexpr (la == 0) n_ext[lb] += world_to_link<lb, S>(motions, Mt).dense();
                else n_ext[lb] += world_to_link<lb, S>(motions, link_to_world<la, S>(motions, Mt)).dense();
              }
              if constexpr (la != 0) n_ext[la] -= Mt.dense();
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
  }
}

template <class T>
[[nodiscard]] std::string describe_state(const T* q, int nq, const T* v, int nv) {
  std::string out = "q = [";
  for (int i = 0; i < nq; ++i) {
    if (i) out += ", ";
    append_number(out, static_cast<long double>(q[i]));
  }
  out += "], v = [";
  for (int i = 0; i < nv; ++i) {
    if (i) out += ", ";
    append_number(out, static_cast<long double>(v[i]));
  }
  out += "]";
  return out;
}
FLANGE_COMMON(std::string describe_state<double>(const double*, int, const double*, int))
/// The state (q, v) as values, for a simulation_error.
template <class T>
[[nodiscard]] std::vector<double> state_values(const T* q, int nq, const T* v, int nv) {
  std::vector<double> x;
  x.reserve(static_cast<std::size_t>(nq + nv));
  for (int i = 0; i < nq; ++i) x.push_back(static_cast<double>(q[i]));
  for (int i = 0; i < nv; ++i) x.push_back(static_cast<double>(v[i]));
  return x;
}
FLANGE_COMMON(std::vector<double> state_values<double>(const double*, int, const double*, int))

}  // namespace flange::detail
