// Branched trees described by a compile-time shape, for law tests and
// benchmarks over many scene shapes: which joint hangs on which, its kind and
// axis, its axis law, the body on it, and the force elements around it.
//
// Joint i (a Revolute or Prismatic named "j<i>") hangs on its parent's
// child-side frame (or the World's frame_b), optionally through a
// FixedTranslation "o<i>", and may be connected either way round. A body
// "b<i>" sits on its child-side frame. Around it there may be a Torque "t<i>"
// between the parent frame and the child-side frame, a line force "s<i>"
// (Spring, Damper or SpringDamper) from the child-side frame to another
// joint's (or the World's), and a WorldForce or WorldTorque "w<i>".
//
// random_tree_shape(seed, n, planar) draws a shape with depth at most 4 and at
// most 3 joints on one frame. A planar shape turns every revolute joint about
// z and slides every prismatic joint along x or y; anything else may take a
// run-time axis. Point masses sit only on prismatic joints, so no revolute
// joint has all the mass behind it on its axis (its mass matrix stays regular).
#pragma once
#include <array>
#include <utility>

#include <boost/hana/concat.hpp>
#include <boost/hana/flatten.hpp>
#include <boost/hana/prepend.hpp>
#include <boost/hana/unpack.hpp>

#include "flange/components/body.hpp"
#include "flange/components/fixed_translation.hpp"
#include "flange/components/world.hpp"
#include "flange/forces/line_force.hpp"
#include "flange/forces/torque.hpp"
#include "flange/forces/world_force.hpp"
#include "flange/joints/prismatic.hpp"
#include "flange/joints/revolute.hpp"
#include "flange/joints/cylindrical.hpp"
#include "flange/joints/free_motion.hpp"
#include "flange/joints/planar.hpp"
#include "flange/joints/spherical.hpp"
#include "flange/joints/universal.hpp"
#include "flange/simulate/system.hpp"

namespace flange::models {

/// Every joint kind, in the order random trees draw them (random_tree_shape)
/// and tests/joint_laws_test.cpp checks them. A new joint is one entry here
/// and one case in tree_joint below. A tree with every_joint draws the
/// first seven kinds as they always were and a later kind from a stream of
/// its own, so the trees of a seed stay what they were when a kind is added.
enum class joint_kind { revolute, prismatic, spherical, universal, cylindrical, planar, free_motion };
inline constexpr int n_joint_kinds = 7;
/// f(integral_constant<joint_kind, K>) for every kind K, in the list's order.
template <class F>
constexpr void for_each_joint_kind(F&& f) {
  [&]<int... K>(std::integer_sequence<int, K...>) {
    (f(std::integral_constant<joint_kind, joint_kind(K)>{}), ...);
  }(std::make_integer_sequence<int, n_joint_kinds>{});
}
/// Whether a joint of kind k may be connected frame_b toward the World in a
/// random tree (Planar and FreeMotion are drawn with frame_a toward it).
constexpr bool drawn_reversible(joint_kind k) { return k != joint_kind::planar && k != joint_kind::free_motion; }

struct tree_shape {
  static constexpr int max_joints = 12;
  int n = 0;
  bool planar = false;
  std::array<int, max_joints> parent{};       ///< −1: the World
  std::array<bool, max_joints> prismatic{};
  std::array<joint_kind, max_joints> kind{};  ///< revolute: Revolute or Prismatic, as prismatic says
  std::array<int, max_joints> axis{};         ///< 0, 1, 2: axis::x, y, z as a type; 3: axis::any
  std::array<int, max_joints> law{};          ///< 0 none, 1 spring-damper, 2 friction
  std::array<bool, max_joints> stops{};       ///< the law within axis_law::limited (Revolute, Prismatic)
  std::array<bool, max_joints> offset{};      ///< a FixedTranslation "o<i>" before the joint
  std::array<bool, max_joints> reversed{};    ///< frame_b faces the World
  std::array<int, max_joints> body{};         ///< 0 J at the frame, 1 cm offset, 2 diagonal J, 3 point mass
  std::array<bool, max_joints> torque{};      ///< a Torque "t<i>" across the joint (and its offset)
  std::array<int, max_joints> line{};         ///< −2 none; else a line force "s<i>" to joint k's child frame (−1: World)
  std::array<int, max_joints> line_law{};     ///< 0 Spring, 1 Damper, 2 SpringDamper
  std::array<int, max_joints> load{};         ///< 0 none, 1 WorldForce, 2 … in frame_b, 3 WorldTorque, 4 … in frame_b
  [[nodiscard]] constexpr int depth(int i) const { return i < 0 ? 0 : 1 + depth(parent[i]); }
  /// Whether joint k hangs (directly or not) on joint i.
  [[nodiscard]] constexpr bool below(int k, int i) const {
    for (int j = k; j >= 0; j = parent[j])
      if (parent[j] == i) return true;
    return false;
  }
};

namespace detail {
struct lcg {
  unsigned long long s;
  constexpr unsigned next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return unsigned(s >> 33);
  }
  constexpr int below(int n) { return int(next() % unsigned(n)); }
};
}  // namespace detail

/// A random tree of n joints (see above); the same seed gives the same
/// shape. With every_joint, the joints are drawn from every kind (a planar
/// shape: Revolute, Prismatic and Planar in the plane).
constexpr tree_shape random_tree_shape(unsigned seed, int n, bool planar, bool every_joint = false,
                                       bool with_stops = false) {
  tree_shape t{};
  t.n = n;
  t.planar = planar;
  detail::lcg r{seed * 2654435761ULL + 12345};
  detail::lcg later{seed * 40503ULL + 977};  // joint kinds beyond the first seven (joint_kind)
  detail::lcg stop{seed * 69069ULL + 4243};  // with_stops: which joints stop (a stream of its own)
  std::array<int, tree_shape::max_joints + 1> children{};  // [0]: the World
  for (int i = 0; i < n; ++i) {
    int p = -1;
    for (int tries = 0; tries < 100; ++tries) {
      p = r.below(i + 1) - 1;
      if (children[p + 1] < 3 && t.depth(p) < 4) break;
    }
    ++children[p + 1];
    t.parent[i] = p;
    t.prismatic[i] = r.below(3) == 0;
    if (planar) t.axis[i] = t.prismatic[i] ? r.below(2) : 2;
    else t.axis[i] = r.below(4);
    t.law[i] = r.below(3);
    t.offset[i] = r.below(3) != 0;
    t.reversed[i] = r.below(4) == 0;
    t.body[i] = r.below(t.prismatic[i] ? 4 : 3);
    t.torque[i] = r.below(3) == 0;
    t.line_law[i] = r.below(3);
    t.load[i] = r.below(3) == 0 ? 1 + r.below(4) : 0;
    if (every_joint) {
      // In a plane: Planar one time in three, else Revolute or Prismatic. In
      // space the first seven kinds as they were always drawn, and a kind
      // added to the list later from a stream of its own.
      auto k = planar ? (r.below(3) == 0 ? joint_kind::planar : joint_kind::revolute) : joint_kind(r.below(7));
      if constexpr (n_joint_kinds > 7) {
        if (!planar && later.below(n_joint_kinds) >= 7) k = joint_kind(7 + later.below(n_joint_kinds - 7));
      }
      t.kind[i] = k == joint_kind::prismatic ? joint_kind::revolute : k;  // as t.prismatic says
      if (t.kind[i] != joint_kind::revolute) {
        t.prismatic[i] = false;
        if (t.body[i] == 3) t.body[i] = 0;  // a point mass needs a joint that does not turn
        if (!drawn_reversible(t.kind[i])) t.reversed[i] = false;
        if (planar) t.axis[i] = 2;
      }
    }
    t.stops[i] = with_stops && t.kind[i] == joint_kind::revolute && stop.below(2) == 0;
  }
  // A line force from joint i's child frame (behind its offset) to a frame
  // that is not below joint i: the path between its ends then crosses the
  // offset, so the ends are apart.
  for (int i = 0; i < n; ++i) {
    t.line[i] = -2;
    if (!t.offset[i] || r.below(3) != 0) continue;
    const int k = r.below(n + 1) - 1;
    t.line[i] = (k == i || t.below(k, i)) ? -1 : k;
  }
  return t;
}

/// The run-time numbers of a tree of N joints.
template <int N>
struct tree_params {
  std::array<Vec3d, N> offset;  ///< o<i>'s d
  std::array<Vec3d, N> axis;    ///< used where the axis is axis::any
  std::array<Vec3d, N> axis2;   ///< a Universal's second axis, a Planar's first direction
  std::array<double, N> m;
  std::array<Mat3d, N> J;
  std::array<Vec3d, N> r_cm;
  std::array<double, N> c, d, q0;  ///< axis laws: stiffness, damping (or viscous friction), rest position
  std::array<double, N> f_c;       ///< Coulomb friction
  std::array<double, N> lower{}, upper{}, k_stop{}, d_stop{};  ///< stops: bounds, stiffness, dissipation
  std::array<double, N> f;         ///< a prismatic joint's force input
  std::array<Vec3d, N> torque;     ///< t<i>'s M_ext
  std::array<double, N> line_c, line_s0, line_d;
  std::array<Vec3d, N> load;       ///< w<i>'s value
  Vec3d g = Vec3d(0, -9.81, 0);
};

namespace detail {
template <tree_shape Sh, int I>
constexpr auto child_frame() {
  if constexpr (Sh.reversed[I]) return indexed_name<"j", I>() + ".frame_a";
  else return indexed_name<"j", I>() + ".frame_b";
}
template <tree_shape Sh, int I>
constexpr auto parent_side_frame() {
  if constexpr (Sh.reversed[I]) return indexed_name<"j", I>() + ".frame_b";
  else return indexed_name<"j", I>() + ".frame_a";
}
/// The frame joint I hangs on: its parent's child-side frame, or the World's.
template <tree_shape Sh, int I>
constexpr auto parent_frame() {
  if constexpr (Sh.parent[I] < 0) return fixed_string("world.frame_b");
  else return child_frame<Sh, Sh.parent[I]>();
}
template <int L>
struct tree_law_of {
  using type = std::conditional_t<L == 0, axis_law::none, std::conditional_t<L == 1, axis_law::spring_damper, axis_law::friction>>;
};
template <int A>
using tree_axis = std::conditional_t<A == 0, axis::x, std::conditional_t<A == 1, axis::y, std::conditional_t<A == 2, axis::z, axis::any>>>;
template <int L, bool Stops = false>
using tree_law = std::conditional_t<
    Stops, axis_law::limited<typename tree_law_of<L>::type>, typename tree_law_of<L>::type>;
template <int L>
using tree_line_law = std::conditional_t<L == 0, line_law::spring, std::conditional_t<L == 1, line_law::damper, line_law::spring_damper>>;

template <tree_shape Sh, int I, int N>
auto tree_joint(const tree_params<N>& p) {
  using A = tree_axis<Sh.axis[I]>;
  using Law = tree_law<Sh.law[I], Sh.stops[I]>;
  constexpr auto name = indexed_name<"j", I>();
  if constexpr (Sh.kind[I] == joint_kind::spherical) {
    return Spherical<name>{};
  } else if constexpr (Sh.kind[I] == joint_kind::universal) {
    return Universal<name, A, axis::any>({.n_a = p.axis[I], .n_b = p.axis2[I]});
  } else if constexpr (Sh.kind[I] == joint_kind::cylindrical) {
    return Cylindrical<name, A>({.n = p.axis[I]});
  } else if constexpr (Sh.kind[I] == joint_kind::planar) {
    if constexpr (Sh.planar) return Planar<name, axis::z, axis::x>{};
    else return Planar<name>({.n = p.axis[I], .n_x = p.axis2[I]});
  } else if constexpr (Sh.kind[I] == joint_kind::free_motion) {
    return FreeMotion<name>{};
  } else if constexpr (Sh.prismatic[I]) {
    using J = Prismatic<name, A, double, Law>;
    typename J::params q{};
    if constexpr (!A::fixed || Sh.law[I] != 0) q.n = p.axis[I];
    q.f = p.f[I];
    if constexpr (Sh.law[I] == 1) {
      q.c = p.c[I];
      q.d = p.d[I];
      q.s0 = p.q0[I];
    } else if constexpr (Sh.law[I] == 2) {
      q.d = p.d[I];
      q.f_c = p.f_c[I];
    }
    if constexpr (Sh.stops[I]) q.stop = {.lower = p.lower[I], .upper = p.upper[I], .stiffness = p.k_stop[I], .dissipation = p.d_stop[I]};
    return J(q);
  } else {
    using J = Revolute<name, A, Law>;
    typename J::params q{};
    if constexpr (!A::fixed || Sh.law[I] != 0) q.n = p.axis[I];
    if constexpr (Sh.law[I] == 1) {
      q.c = p.c[I];
      q.d = p.d[I];
      q.phi0 = p.q0[I];
    } else if constexpr (Sh.law[I] == 2) {
      q.d = p.d[I];
      q.f_c = p.f_c[I];
    }
    if constexpr (Sh.stops[I]) q.stop = {.lower = p.lower[I], .upper = p.upper[I], .stiffness = p.k_stop[I], .dissipation = p.d_stop[I]};
    return J(q);
  }
}

template <tree_shape Sh, int I, int N>
auto tree_body(const tree_params<N>& p) {
  constexpr auto name = indexed_name<"b", I>();
  if constexpr (Sh.body[I] == 0) return Body<name>({.m = p.m[I], .J = p.J[I]});
  else if constexpr (Sh.body[I] == 1) return Body<name, cm::offset>({.m = p.m[I], .J = p.J[I], .r_cm = p.r_cm[I]});
  else if constexpr (Sh.body[I] == 2)
    return Body<name, cm::at_frame, inertia_kind::diagonal>({.m = p.m[I], .J = Mat3d(p.J[I].diagonal().asDiagonal())});
  else return PointMass<name>({.m = p.m[I]});
}

/// The components and connections that joint I brings, as a tuple.
template <tree_shape Sh, int I, int N>
auto tree_part(const tree_params<N>& p) {
  namespace hana = boost::hana;
  constexpr auto pf = parent_frame<Sh, I>();
  constexpr auto cf = child_frame<Sh, I>();
  constexpr auto ps = parent_side_frame<Sh, I>();
  auto core = [&] {
    if constexpr (Sh.offset[I]) {
      constexpr auto o = indexed_name<"o", I>();
      return hana::make_tuple(FixedTranslation<o>({.d = p.offset[I]}), tree_joint<Sh, I>(p), tree_body<Sh, I>(p),
                              connect<pf, o + ".frame_a">, connect<o + ".frame_b", ps>,
                              connect<cf, indexed_name<"b", I>() + ".frame_a">);
    } else {
      return hana::make_tuple(tree_joint<Sh, I>(p), tree_body<Sh, I>(p), connect<pf, ps>,
                              connect<cf, indexed_name<"b", I>() + ".frame_a">);
    }
  }();
  auto torque_part = [&] {
    constexpr auto t = indexed_name<"t", I>();
    if constexpr (Sh.torque[I])
      return hana::make_tuple(Torque<t>({.M_ext = p.torque[I]}), connect<pf, t + ".frame_a">, connect<cf, t + ".frame_b">);
    else return hana::make_tuple();
  }();
  auto line_part = [&] {
    constexpr auto s = indexed_name<"s", I>();
    if constexpr (Sh.line[I] >= -1) {
      constexpr auto other = [] {
        if constexpr (Sh.line[I] < 0) return fixed_string("world.frame_b");
        else return child_frame<Sh, (Sh.line[I] < 0 ? 0 : Sh.line[I])>();
      }();
      using L = LineForce<s, tree_line_law<Sh.line_law[I]>>;
      typename L::params q{};
      if constexpr (Sh.line_law[I] != 1) {
        q.c = p.line_c[I];
        q.s0 = p.line_s0[I];
      }
      if constexpr (Sh.line_law[I] != 0) q.d = p.line_d[I];
      return hana::make_tuple(L(q), connect<cf, s + ".frame_a">, connect<other, s + ".frame_b">);
    } else {
      return hana::make_tuple();
    }
  }();
  auto load_part = [&] {
    constexpr auto w = indexed_name<"w", I>();
    constexpr int k = Sh.load[I];
    if constexpr (k == 0) return hana::make_tuple();
    else {
      using What = std::conditional_t<(k <= 2), load::force, load::torque>;
      using Frame = std::conditional_t<(k % 2 == 0), resolve::frame_b, resolve::world>;
      return hana::make_tuple(WorldLoad<w, What, Vec3d, Frame>({.value = p.load[I]}), connect<cf, w + ".frame_b">);
    }
  }();
  return hana::concat(hana::concat(core, torque_part), hana::concat(line_part, load_part));
}
}  // namespace detail

/// The scene of a tree shape with its numbers.
template <tree_shape Sh>
auto tree(const tree_params<Sh.n>& p) {
  namespace hana = boost::hana;
  auto parts = [&]<int... I>(std::integer_sequence<int, I...>) {
    return hana::flatten(hana::make_tuple(detail::tree_part<Sh, I>(p)...));
  }(std::make_integer_sequence<int, Sh.n>{});
  return hana::unpack(hana::prepend(parts, World<"world">({.g = p.g})), [](auto... a) { return scene(std::move(a)...); });
}

}  // namespace flange::models
