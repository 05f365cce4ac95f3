// Closed kinematic loops: the constraints a cut joint puts on the tree.
//
// topology.hpp cuts each loop at a joint (the last joint written in it, or
// another where that one cannot be cut or would leave a tree joint moving no
// mass) and leaves that joint out of the tree and of the state. What the cut joint
// would have done becomes constraints on the tree's coordinates: its two
// frames, both placed by the tree, must stay related as the joint allows.
// What a joint leaves free is its as_cut (core/joint.hpp); the rest is
// locked, row by row:
//
//   translations  the origins meet:            d = r_b − r_a = 0        (3 rows)
//                 or only across the axis n:   u_i·d = 0, u_i ⟂ n fixed in frame_a   (2)
//                 or only along n:             n_a·d = 0                (1; a Planar joint)
//                 or not at all                                         (0; FreeMotion)
//   rotations     frame_b keeps n of frame_a:  u_i·n_b = 0, u_i ⟂ n_a   (2)
//                 or two axes keep their angle: n_a·n_b = n_a·n_b at q = 0   (1; Universal)
//                 or every axis:               e_j,a·e_k,b = 0 for (j, k) = (1, 2), (2, 0), (0, 1)   (3)
//
// So a cut Revolute gives 5 rows, a Prismatic 5, a Spherical 3, a
// Cylindrical 4, a Universal 4, a Planar 3 and a FreeMotion none. A planar
// scene (every joint's axis the same coordinate axis k, from the types:
// algebra.hpp) keeps only the in-plane rows: a revolute cut gives 2 rows
// instead of 5, a prismatic 2, a Planar joint about k none, and no row is
// redundant.
//
// Each row is Φ_i(q) = u·w for two vectors that turn with the frames (or
// with the World); its rate is Φ̇_i = (ω_u × u)·w + u·ẇ exactly: coefficients
// on the two frames' motions. G's row is those coefficients times the motion
// subspaces of the joints between the World and each frame; Ġ·v comes from
// the frames' bias accelerations at v̇ = 0 (the Newton–Euler forward step).
// The coefficients times λ are also the forces the cut joint exerts.
//
// The constrained accelerations and the projection onto the constraints
// are in loop_solve.hpp.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <limits>
#include <string>
#include <utility>

#include "flange/detail/inline.hpp"
#include "flange/dynamics/algebra.hpp"
#include "flange/dynamics/kinematics.hpp"
#include "flange/dynamics/links.hpp"

namespace flange::detail {

/// What the dynamics know of cut K at compile time.
template <class S, int K>
struct cut_info {
  static constexpr int joint = S::tree.cuts[K];
  using joint_type = typename S::template component_type<joint>;
  static constexpr bool supported = cuttable<joint_type>;
  static constexpr cut_freedom freedom = [] {
    if constexpr (cuttable<joint_type>) return cut_freedom(joint_type::as_cut);
    else return cut_freedom{3, 3};  // reported by the scene; no rows
  }();
  static constexpr int set_a = S::topology.set_of[S::table.frame_base[joint]];
  static constexpr int set_b = S::topology.set_of[S::table.frame_base[joint] + 1];
  static constexpr int link_a = S::tree.set_link[set_a];
  static constexpr int link_b = S::tree.set_link[set_b];
  /// The plane's normal axis for a planar scene, −1 otherwise.
  static constexpr int plane = planar_axis<S>();
  /// In a planar scene only the in-plane rows: 2 translations less those
  /// left free (a Planar joint about the normal leaves both), 1 rotation.
  static constexpr int translation_rows = plane >= 0 ? std::max(0, 2 - freedom.translations) : 3 - freedom.translations;
  static constexpr int rotation_rows = plane >= 0 ? std::max(0, 1 - freedom.rotations) : 3 - freedom.rotations;
  static constexpr int rows = translation_rows + rotation_rows;
};

/// The first constraint row of cut K.
template <class S, int K>
constexpr int cut_row() {
  if constexpr (K == 0) return 0;
  else return cut_row<S, K - 1>() + cut_info<S, K - 1>::rows;
}

/// The number of constraint rows of all the scene's loops.
template <class S>
constexpr int n_constraints() {
  return cut_row<S, S::tree.n_cuts>();
}

/// Whether the scene's loops constrain anything (a loop closed by a
/// FreeMotion, or by a Planar joint in its own plane, does not).
template <class S>
inline constexpr bool has_loops = n_constraints<S>() > 0;

/// The first cut whose joint type cannot close a loop (−1: none).
template <class S>
constexpr int first_uncuttable_joint() {
  return []<int... K>(std::integer_sequence<int, K...>) {
    int found = -1;
    ((found < 0 && !cut_info<S, K>::supported ? found = cut_info<S, K>::joint : 0), ...);
    return found;
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
}

/// f(integral_constant<K>) for each cut K.
template <class S, class F>
FLANGE_INLINE void for_cuts(F&& f) {
  [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, K>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
}

/// A connection set's pose and motion in the world: R rotates world into
/// the set's coordinates; r, its origin's velocity v, ω, and the bias
/// accelerations ω̇ and a (at v̇ = 0, without gravity) are in world
/// coordinates.
template <class T>
struct set_motion {
  Mat3<T> R;
  Vec3<T> r, v, w, wd, a;
};

/// The links' world poses and velocities, and their bias accelerations.
template <class S, class T, class Motions>
struct link_states {
  std::array<link_pose<T>, S::tree.n_links> pose;
  std::array<Vec3<T>, S::tree.n_links> wd, a;
};
template <class S, class T, class Motions>
FLANGE_INLINE link_states<S, T, Motions> loop_link_states(const Motions& motions, const T* v) {
  link_states<S, T, Motions> r{link_poses<S, T>(motions, v), {}, {}};
  // ω̇ and a at v̇ = 0, without gravity: the bias accelerations.
  link_accelerations<S, T>(motions, v, no_rates{}, link_kinematics{zero_vec<T>{}, zero_vec<T>{}, zero_vec<T>{}}, r.wd,
                           r.a);
  return r;
}

/// A set's pose and velocity from its link's (set_motion's R, r, v and ω;
/// its bias accelerations are left zero).
template <class S, int Set, class T>
FLANGE_INLINE set_motion<T> set_velocity(const S& scene, const link_pose<T>& p) {
  constexpr int K = planar_axis<S>();
  const Vec3<T> o = scene.model().set_offset[Set].template cast<T>();
  auto R = [&] {  // a set that does not turn against its link (the types say so) has its link's R
    if constexpr (set_rotation_kind<S>(Set) == -2) return p.R;
    else return Mat3<T>(scene.model().set_rotation[Set].template cast<T>() * p.R);
  };
  return {R(),
          point_position<K>(p, o),
          point_velocity<K>(p, o),
          angular_in_world<K>(p, p.w),
          Vec3<T>::Zero(),
          Vec3<T>::Zero()};
}

/// A set's pose, motion and bias accelerations (set_motion) from its
/// link's. A set on the World is fixed: its R and r, and zeros, with no
/// arithmetic (the loops' passes put the World at rest). Always inlined,
/// so that what a cut's rows do not read is not computed.
template <class S, int Set, class T, class LS>
FLANGE_INLINE set_motion<T> motion_of_set(const S& scene, const LS& ls) {
  constexpr int L = S::tree.set_link[Set];
  if constexpr (L == 0) {
    Mat3<T> R;
    if constexpr (set_rotation_kind<S>(Set) == -2) R.setIdentity();
    else R = scene.model().set_rotation[Set].template cast<T>();
    const Vec3<T> zero = Vec3<T>::Zero();
    return {R, scene.model().set_offset[Set].template cast<T>(), zero, zero, zero, zero};
  } else {
    const link_pose<T>& p = ls.pose[L];
    set_motion<T> m = set_velocity<S, Set, T>(scene, p);
    constexpr int K = planar_axis<S>();
    m.wd = angular_in_world<K>(p, ls.wd[L]);
    m.a = point_acceleration<K>(p, Vec3<T>(scene.model().set_offset[Set].template cast<T>()), ls.wd[L], ls.a[L]);
    return m;
  }
}

/// One constraint row: Φ, Φ̇, the bias Φ̈ at v̇ = 0 (= Ġ·v), and the row's
/// coefficients on the two frames' motions (world coordinates, at their
/// origins): Φ̇ = wa·ω_a + va·v_a + wb·ω_b + vb·v_b. The same coefficients,
/// times λ, are the torque and force the cut joint exerts on each frame.
template <class T>
struct constraint_row {
  T phi, phid, bias;
  Vec3<T> wa, va, wb, vb;
};

/// A row u·d: u fixed in frame a (u̇ = ω_a × u) or in the World, d = r_b − r_a.
template <class T, bool Turning>
FLANGE_INLINE constraint_row<T> translation_row(const Vec3<T>& u, const set_motion<T>& a, const set_motion<T>& b) {
  const Vec3<T> d = b.r - a.r, dd = b.v - a.v, dda = b.a - a.a;
  constraint_row<T> r;
  r.phi = u.dot(d);
  r.va = -u;
  r.vb = u;
  r.wb = Vec3<T>::Zero();
  if constexpr (Turning) {
    const Vec3<T> ud = a.w.cross(u), ux = u.cross(d);
    r.wa = ux;
    r.phid = ud.dot(d) + u.dot(dd);
    r.bias = a.wd.dot(ux) + a.w.dot(ud.cross(d) + u.cross(dd)) + ud.dot(dd) + u.dot(dda);
  } else {
    r.wa = Vec3<T>::Zero();
    r.phid = u.dot(dd);
    r.bias = u.dot(dda);
  }
  return r;
}
/// A row u·w: u fixed in frame a, w fixed in frame b.
template <class T>
FLANGE_INLINE constraint_row<T> rotation_row(const Vec3<T>& u, const Vec3<T>& w, const set_motion<T>& a, const set_motion<T>& b) {
  const Vec3<T> wu = w.cross(u), dw = b.w - a.w;
  const Vec3<T> ud = a.w.cross(u), wdot = b.w.cross(w);
  constraint_row<T> r;
  r.phi = u.dot(w);
  r.wa = -wu;
  r.wb = wu;
  r.va = r.vb = Vec3<T>::Zero();
  r.phid = dw.dot(wu);
  r.bias = (b.wd - a.wd).dot(wu) + dw.dot(wdot.cross(u) + w.cross(ud));
  return r;
}

/// Cut K's rows from its two frames' motions.
template <class S, int K, class T>
FLANGE_INLINE void cut_constraint(const S& scene, const set_motion<T>& a, const set_motion<T>& b, constraint_row<T>* rows) {
  using CI = cut_info<S, K>;
  const auto& joint = scene.template component<CI::joint>();
  int i = cut_row<S, K>();
  auto in_a = [&](const Vec3d& e) { return Vec3<T>(a.R.transpose() * e.template cast<T>()); };
  auto in_b = [&](const Vec3d& e) { return Vec3<T>(b.R.transpose() * e.template cast<T>()); };
  if constexpr (CI::freedom.translations == 0) {
    for (int c = 0; c < 3; ++c)
      if (c != CI::plane) rows[i++] = translation_row<T, false>(Vec3<T>::Unit(c), a, b);
  } else if constexpr (CI::translation_rows > 0) {
    if constexpr (CI::plane >= 0) {
      rows[i++] = translation_row<T, true>(in_a(Vec3d::Unit(CI::plane).cross(joint.n())), a, b);
    } else if constexpr (CI::freedom.translations == 2) {  // in the plane normal to n: off it, not
      rows[i++] = translation_row<T, true>(in_a(joint.n()), a, b);
    } else {
      Vec3d e1, e2;
      complete_basis(joint.n(), e1, e2);
      rows[i++] = translation_row<T, true>(in_a(e1), a, b);
      rows[i++] = translation_row<T, true>(in_a(e2), a, b);
    }
  }
  if constexpr (CI::rotation_rows > 0) {
    if constexpr (CI::freedom.rotations == 2) {  // n_a and n_b keep the angle between them
      rows[i] = rotation_row<T>(in_a(joint.n_a()), in_b(joint.n_b()), a, b);
      rows[i++].phi -= T(joint.n_a().dot(joint.n_b()));
    } else if constexpr (CI::freedom.rotations == 1) {
      Vec3d e1, e2;
      complete_basis(joint.n(), e1, e2);
      const Vec3<T> n = in_b(joint.n());
      rows[i++] = rotation_row<T>(in_a(e1), n, a, b);
      rows[i++] = rotation_row<T>(in_a(e2), n, a, b);
    } else if constexpr (CI::plane >= 0) {
      rows[i++] = rotation_row<T>(in_a(Vec3d::Unit((CI::plane + 1) % 3)), in_b(Vec3d::Unit((CI::plane + 2) % 3)), a, b);
    } else {
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitY()), in_b(Vec3d::UnitZ()), a, b);
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitZ()), in_b(Vec3d::UnitX()), a, b);
      rows[i++] = rotation_row<T>(in_a(Vec3d::UnitX()), in_b(Vec3d::UnitY()), a, b);
    }
  }
}

/// A cut joint's coordinates and rates as its frames give them (its
/// cut_state: what recover reports for it), and each rate's coefficients on
/// the two frames' motions, as a constraint row's: rate_i = wa·ω_a + va·v_a
/// + wb·ω_b + vb·v_b (world coordinates, at the frames' origins).
template <class J>
struct cut_reading {
  std::array<double, J::nq> q;
  std::array<double, J::nv> v;
  std::array<constraint_row<double>, J::nv> rows;
};
/// The joint's coordinates q and rates v from its two frames' motions: its
/// cut_state at frame_b's pose and motion relative to frame_a.
template <class J, class T>
void cut_state_between(const J& joint, const set_motion<T>& a, const set_motion<T>& b, T* q, T* v) {
  const Mat3<T> R = b.R * a.R.transpose();
  const Vec3<T> d = b.r - a.r;
  const Vec3<T> p = a.R * d, w = a.R * (b.w - a.w), pd = a.R * (b.v - a.v - a.w.cross(d));
  joint.cut_state(R, p, w, pd, q, v);
}

template <class J>
cut_reading<J> read_cut(const J& joint, const set_motion<double>& a, const set_motion<double>& b) {
  cut_reading<J> r;
  cut_state_between(joint, a, b, r.q.data(), r.v.data());
  const Mat3d R = b.R * a.R.transpose();
  const Vec3d d = b.r - a.r, p = a.R * d;
  // The rates are linear in (w, ṗ), frame_a coordinates: their coefficients
  // from unit motions, turned into the world's (ṗ = R_a·(v_b − v_a − ω_a × d)).
  std::array<Vec3d, J::nv> lw, lp;
  for (int e = 0; e < 6; ++e) {
    Vec3d we = Vec3d::Zero(), pe = Vec3d::Zero();
    (e < 3 ? we : pe)(e % 3) = 1;
    std::array<double, J::nq> q;
    std::array<double, J::nv> v;
    joint.cut_state(R, p, we, pe, q.data(), v.data());
    for (int i = 0; i < J::nv; ++i) (e < 3 ? lw[i] : lp[i])(e % 3) = v[i];
  }
  for (int i = 0; i < J::nv; ++i) {
    const Vec3d n = a.R.transpose() * lw[i], f = a.R.transpose() * lp[i];
    auto& row = r.rows[i];
    row.phi = r.q[i < J::nq ? i : 0];
    row.phid = r.v[i];
    row.bias = 0;
    row.wa = -n - d.cross(f);
    row.va = -f;
    row.wb = n;
    row.vb = f;
  }
  return r;
}

/// Cut K's frames' poses and velocities at (q, v) in scalar T: one pass
/// over the tree's poses and velocities, no accelerations.
template <class S, int K, class T>
std::pair<set_motion<T>, set_motion<T>> cut_frames_at(const S& scene, const T* q, const T* v) {
  using CI = cut_info<S, K>;
  const auto motions = link_motions<spatial_algebra, T, true>(scene, q);
  const auto poses = link_poses<S, T>(motions, v);
  return {set_velocity<S, CI::set_a, T>(scene, poses[S::tree.set_link[CI::set_a]]),
          set_velocity<S, CI::set_b, T>(scene, poses[S::tree.set_link[CI::set_b]])};
}

/// Cut K's joint as its frames place it at (q, v).
template <class S, int K>
auto read_cut_at(const S& scene, const double* q, const double* v) {
  const auto [a, b] = cut_frames_at<S, K, double>(scene, q, v);
  return read_cut(scene.template component<cut_info<S, K>::joint>(), a, b);
}

/// Cut K's coordinates and rates at (q, v) in scalar T (declared in
/// scene/named_state.hpp, for inputs that read a cut joint by name).
template <class S, int K, class T>
void cut_joint_values(const S& scene, const T* q, const T* v, T* cq, T* cv) {
  const auto [a, b] = cut_frames_at<S, K, T>(scene, q, v);
  cut_state_between(scene.template component<cut_info<S, K>::joint>(), a, b, cq, cv);
}

/// How cut K's frames keep the axes its rotation rows lock. The rows ask
/// an axis of frame b to stay normal to two axes of frame a (or the axes'
/// cross terms to vanish), which frame b turned half a turn also meets: the
/// joint's axis reversed, another mechanism. The smallest cosine between a
/// locked axis in frame a and the same axis in frame b: 1 closed as the
/// joint is, −1 turned over; 1 where no rotation is locked (or a
/// Universal's, whose row keeps an angle, not an axis).
template <class S, int K>
double cut_alignment(const S& scene, const set_motion<double>& a, const set_motion<double>& b) {
  using CI = cut_info<S, K>;
  const auto& joint = scene.template component<CI::joint>();
  auto cosine = [&](const Vec3d& e) { return (a.R.transpose() * e).dot(b.R.transpose() * e); };
  if constexpr (CI::rotation_rows == 0 || CI::freedom.rotations == 2) {
    return 1.0;
  } else if constexpr (CI::freedom.rotations == 1) {
    return cosine(joint.n());
  } else if constexpr (CI::plane >= 0) {
    return cosine(Vec3d::Unit((CI::plane + 1) % 3));
  } else {
    return std::min({cosine(Vec3d::UnitX()), cosine(Vec3d::UnitY()), cosine(Vec3d::UnitZ())});
  }
}

/// The first cut whose frames are turned over at q (cut_alignment below 0), or −1.
template <class S>
int turned_over_cut(const S& scene, const double* q) {
  std::array<double, S::n_v> zero{};
  const auto motions = link_motions<spatial_algebra, double, true>(scene, q);
  const auto ls = loop_link_states<S, double>(motions, zero.data());
  int found = -1;
  for_cuts<S>([&](auto k) {
    constexpr int K = decltype(k)::value;
    using CI = cut_info<S, K>;
    if constexpr (CI::rotation_rows > 0)
      if (found < 0 && !(cut_alignment<S, K>(scene, motion_of_set<S, CI::set_a, double>(scene, ls),
                                             motion_of_set<S, CI::set_b, double>(scene, ls)) > 0))
        found = K;
  });
  return found;
}

/// The links from the World's child down to link Link (Link included;
/// none for the World): the links whose joints move a frame on Link.
template <class S, int Link>
constexpr auto path_from_root() {
  constexpr int depth = [] {
    int d = 0;
    for (int L = Link; L > 0; L = S::tree.link_parent[L]) ++d;
    return d;
  }();
  std::array<int, depth> p{};
  int i = depth;
  for (int L = Link; L > 0; L = S::tree.link_parent[L]) p[--i] = L;
  return p;
}

/// Adds to G's row the row's coefficients (n on ω, f on the velocity of the
/// point p) times the motion subspace of every joint between the World and
/// link Link: the columns J's of a frame on that link, rate j's at
/// row[j·stride]. Only the links on that path are visited (and
/// instantiated).
template <class S, int Link, class T, class Motions, class Poses>
FLANGE_INLINE void add_frame_jacobian(const Motions& motions, const Poses& pose, const Vec3<T>& n, const Vec3<T>& f,
                                      const Vec3<T>& p, T* row, int stride = 1) {
  static constexpr auto path = path_from_root<S, Link>();
  auto add = [&]<int L>(std::integral_constant<int, L>) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, L>;
    const auto& m = std::get<L - 1>(motions);
    const link_pose<T>& P = pose[L];
    // With the point's lever arm folded into the torque: n·ω + f·(v + ω × (p − r)) = (n + (p − r) × f)·ω + f·v.
    // In a planar scene ω is along the normal k and every R turns about k:
    // of R·(n + (p − r) × f) only component k is read, R·f stays in the
    // plane (the typed forms of kinematics.hpp).
    constexpr int k = planar_axis<S>();
    constexpr int in_plane = k >= 0 ? 7 & ~(1 << k) : 7;
    const auto& R = typed_rotation<k>(P);
    const auto nn = rot(R, typed_angular<k>(Vec3<T>(n + (p - P.r).cross(f))));
    const auto ff = rot(R, to_svec<in_plane>(f));
    [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
      // Each column's typed parts (a revolute's along one axis, no linear
      // part) pick the components of nn and ff that are computed at all.
      ((row[(LI::v + K) * stride] += [&] {
         const auto c = m.template col<K>();
         return value_of<T>(dot(nn, c.ang) + dot(ff, c.lin));
       }()),
       ...);
    }(std::make_integer_sequence<int, LI::nv>{});
  };
  [&]<std::size_t... I>(std::index_sequence<I...>) FLANGE_INLINE_LAMBDA {
    (add(std::integral_constant<int, path[I]>{}), ...);
  }(std::make_index_sequence<path.size()>{});
}

/// The loops' constraints at (q, v): Φ(q), Φ̇ = G·v, G, Ġ·v, and each row's
/// coefficients.
template <class S, class T>
struct loop_terms {
  static constexpr int m = n_constraints<S>(), n = S::n_v;
  std::array<T, m> phi, phid, bias;
  Eigen::Matrix<T, m, n> G;
  std::array<constraint_row<T>, m> rows;
};

template <class S, class T, class Motions>
FLANGE_INLINE loop_terms<S, T> loop_kinematics_at(const S& scene, const Motions& motions, const T* v) {
  constexpr int m = n_constraints<S>();
  const auto ls = loop_link_states<S, T>(motions, v);
  loop_terms<S, T> r;
  r.G.setZero();
  for_cuts<S>([&](auto k) {
    using CI = cut_info<S, decltype(k)::value>;
    if constexpr (CI::rows > 0) {
      const auto a = motion_of_set<S, CI::set_a, T>(scene, ls);
      const auto b = motion_of_set<S, CI::set_b, T>(scene, ls);
      cut_constraint<S, decltype(k)::value>(scene, a, b, r.rows.data());
      for (int i = cut_row<S, decltype(k)::value>(); i < cut_row<S, decltype(k)::value>() + CI::rows; ++i) {
        const auto& w = r.rows[i];
        T* g = r.G.data() + i;  // column-major: row i, stride m
        add_frame_jacobian<S, CI::link_a>(motions, ls.pose, w.wa, w.va, a.r, g, m);
        add_frame_jacobian<S, CI::link_b>(motions, ls.pose, w.wb, w.vb, b.r, g, m);
      }
    }
  });
  for (int i = 0; i < m; ++i) {
    r.phi[i] = r.rows[i].phi;
    r.phid[i] = r.rows[i].phid;
    r.bias[i] = r.rows[i].bias;
  }
  return r;
}

/// The same from (q, v).
template <class S, class T>
loop_terms<S, T> loop_kinematics(const S& scene, const T* q, const T* v) {
  const auto motions = link_motions<spatial_algebra, T, true>(scene, q);
  return loop_kinematics_at<S>(scene, motions, v);
}

}  // namespace flange::detail
