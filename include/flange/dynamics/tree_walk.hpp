// Compile-time facts about one link of the kinematic tree, and the loops over
// links that the compiler unrolls (parents before children, or the reverse).
#pragma once
#include <tuple>
#include <utility>

#include "flange/components/frame_kinematics.hpp"
#include "flange/dynamics/joint_transform.hpp"
#include "flange/math/axial.hpp"
#include "flange/errors.hpp"

namespace flange::detail {

template <class S, int L>
struct link_info {
  static constexpr auto& tree = S::tree;
  static constexpr int joint = tree.link_joint[L];
  using joint_type = typename S::template component_type<joint>;
  static constexpr int dir = tree.link_dir[L];
  static constexpr int parent = tree.link_parent[L];
  static constexpr int q = tree.q_index[joint];
  static constexpr int parent_set = tree.link_parent_set[L];
  /// Whether the joint sits away from its parent link's origin (behind a
  /// FixedTranslation); if not, that offset is known to be zero.
  static constexpr bool has_offset = tree.set_parent[parent_set] >= 0;
  template <class T>
  using transform = joint_transform<joint_type, (dir > 0 ? 1 : -1), T>;
};

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
/// Whether any force element needs the frames' positions and velocities.
template <class S>
constexpr bool has_motion_forces() {
  return []<int... C>(std::integer_sequence<int, C...>) {
    return (false || ... || [] {
      using Comp = typename S::template component_type<C>;
      if constexpr (Comp::kind == role::force) return Comp::needs_motion && force_acts<S, C>();
      else return false;
    }());
  }(std::make_integer_sequence<int, S::n_components>{});
}

/// What is known about each link before any number is seen: which quantities
/// are identically zero in the bias pass (q̈ = 0), and which the mass matrix
/// needs. The recursive algorithms skip what these flags rule out, so a link
/// behind a prismatic joint on the World does no angular arithmetic at all.
template <class S>
struct link_flags {
  static constexpr int NL = S::tree.n_links;
  struct table {
    std::array<bool, NL> w_zero{};    ///< ω ≡ 0: no revolute joint on the path to the World
    std::array<bool, NL> wd_zero{};   ///< ω̇ ≡ 0 when q̈ = 0
    std::array<bool, NL> p_zero{};    ///< the link origin coincides with its joint's parent-side frame… and that frame with the parent origin
    std::array<bool, NL> need_I{};    ///< the mass matrix needs the composite rotational inertia
    std::array<bool, NL> has_ext{};   ///< a force element acts on the link (a torque about its origin)
    std::array<bool, NL> has_ext_f{}; ///< … with a force (line forces, world forces)
    std::array<bool, NL> need_f{};    ///< the link force f is used (prismatic joint, or passed to a parent)
    std::array<int, NL> I_kind{};     ///< the link's own rotational inertia about its origin: 0 zero, 1 diagonal, 2 dense
    std::array<bool, NL> h_zero{};    ///< the link's own first moment m·c is zero (all its mass at its origin)
    std::array<int, NL> w_axis{};     ///< ω is axial along this coordinate axis (−1: dense)
    std::array<int, NL> wd_axis{};    ///< ω̇ (q̈ = 0) is axial along this coordinate axis (−1: dense)
  };
  static constexpr table value = [] {
    table t{};
    t.w_zero[0] = t.wd_zero[0] = true;
    t.w_axis[0] = t.wd_axis[0] = -1;
    [&]<int... L>(std::integer_sequence<int, L...>) {
      (
          [&] {
            using LI = link_info<S, L + 1>;
            using J = typename LI::joint_type;
            constexpr bool rev = J::type == joint_type::revolute;
            constexpr int P = LI::parent;
            constexpr int axis = [] {
              if constexpr (J::axis_type::fixed) return J::axis_type::index;
              else return -1;
            }();
            t.w_zero[L + 1] = t.w_zero[P] && !rev;
            if (rev) {
              // ω = E·ω_P + n·q̇ stays along e_i when ω_P does; then ω × n = 0
              // and ω̇ = E·ω̇_P (q̈ = 0).
              const bool parallel = axis >= 0 && (t.w_zero[P] || t.w_axis[P] == axis);
              t.w_axis[L + 1] = parallel ? axis : -1;
              t.wd_zero[L + 1] = t.wd_zero[P] && (t.w_zero[P] || parallel);
              t.wd_axis[L + 1] = parallel && t.wd_axis[P] == axis ? axis : -1;
            } else {
              t.w_axis[L + 1] = t.w_axis[P];
              t.wd_zero[L + 1] = t.wd_zero[P];
              t.wd_axis[L + 1] = t.wd_axis[P];
            }
            t.p_zero[L + 1] = rev && !LI::has_offset;
            t.need_I[L + 1] = rev || t.need_I[P];
            t.need_f[L + 1] = !rev || P != 0;
          }(),
          ...);
    }(std::make_integer_sequence<int, NL - 1>{});
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force) {
              if constexpr (force_acts<S, C>())
                for (int l : force_links<S, C>()) {
                  t.has_ext[l] = true;
                  if constexpr (Comp::exerts_force) t.has_ext_f[l] = true;
                }
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    t.has_ext[0] = t.has_ext_f[0] = false;  // the World takes what it is given
    // Inertia structure from the bodies' types: a body at its link's origin
    // (on the link's root connection set, no centre-of-mass offset) adds
    // nothing to h and its own J to I; anything else makes both dense.
    for (int L = 0; L < NL; ++L) t.h_zero[L] = true;
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::body) {
              const int set = S::topology.set_of[S::table.frame_base[C]];
              const int L = S::tree.set_link[set];
              if (L < 0) return;
              const bool at_origin = S::tree.set_parent[set] < 0 && !Comp::has_cm_offset;
              const int kind = !at_origin ? 2 : Comp::is_point ? 0 : Comp::is_diagonal ? 1 : 2;
              t.I_kind[L] = kind > t.I_kind[L] ? kind : t.I_kind[L];
              t.h_zero[L] = t.h_zero[L] && at_origin;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    return t;
  }();
};

/// The pairs of joints (q indices) on different branches: neither link is an
/// ancestor of the other, so their mass-matrix entry is zero. The
/// composite-rigid-body algorithm writes only ancestor pairs; these are the
/// rest (none for a chain).
template <class S>
constexpr auto branch_pairs() {
  constexpr auto& tree = S::tree;
  constexpr int NL = tree.n_links;
  constexpr int count = [] {
    int n = 0;
    for (int a = 1; a < NL; ++a)
      for (int b = a + 1; b < NL; ++b) {
        bool related = false;
        for (int x = b; x > 0; x = tree.link_parent[x]) related = related || x == a;
        n += !related;
      }
    return n;
  }();
  std::array<std::pair<int, int>, count> pairs{};
  int k = 0;
  for (int a = 1; a < NL; ++a)
    for (int b = a + 1; b < NL; ++b) {
      bool related = false;
      for (int x = b; x > 0; x = tree.link_parent[x]) related = related || x == a;
      if (!related) pairs[k++] = {tree.q_index[tree.link_joint[a]], tree.q_index[tree.link_joint[b]]};
    }
  return pairs;
}

/// Writes the mass matrix's zeros between branches (see branch_pairs).
template <class S, class MM>
void zero_branch_pairs(MM& M) {
  constexpr auto pairs = branch_pairs<S>();
  for (const auto& [i, j] : pairs) M(i, j) = M(j, i) = 0;
}

/// acc += v, or acc = v when nothing has been summed yet: adding to a zero
/// the compiler cannot see (IEEE: 0 + −0 = +0) costs as much as any term.
template <bool Has, class V>
void accumulate(V& acc, const V& v) {
  if constexpr (Has) acc += v;
  else acc = v;
}

/// I·v for a link's own inertia whose structure link_flags know: nothing for
/// zero, three products for diagonal.
template <int Kind, class T, class M, class V>
Vec3<T> inertia_times(const M& I, const V& v) {
  if constexpr (Kind == 1) return I.diagonal().cwiseProduct(dense(v));
  else return mul<T>(I, v);
}

/// f(integral_constant<L>) for L = 1 … n_links−1, parents first.
template <class S, class F>
void for_links(F&& f) {
  [&]<int... L>(std::integer_sequence<int, L...>) {
    (f(std::integral_constant<int, L + 1>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}
/// The same, children first.
template <class S, class F>
void for_links_reverse(F&& f) {
  [&]<int... L>(std::integer_sequence<int, L...>) {
    (f(std::integral_constant<int, S::tree.n_links - 1 - L>{}), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}

/// The joint transforms of all links at q, as a tuple (link L at L−1).
template <class S, class T>
auto joint_transforms(const S& scene, const T* q) {
  return [&]<int... L>(std::integer_sequence<int, L...>) {
    return std::tuple<typename link_info<S, L + 1>::template transform<T>...>{
        typename link_info<S, L + 1>::template transform<T>(
            scene.template component<link_info<S, L + 1>::joint>(), q[link_info<S, L + 1>::q])...};
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}

/// A vector in world coordinates, in link L's coordinates (and back).
template <int L, class S, class X, class T>
Vec3<T> world_to_link(const X& xf, const Vec3<T>& v) {
  if constexpr (L == 0) return v;
  else return std::get<L - 1>(xf).rot(world_to_link<link_info<S, L>::parent, S>(xf, v));
}
template <int L, class S, class X, class T>
Vec3<T> link_to_world(const X& xf, const Vec3<T>& v) {
  if constexpr (L == 0) return v;
  else return link_to_world<link_info<S, L>::parent, S>(xf, std::get<L - 1>(xf).rot_t(v));
}

/// Positions, orientations and velocities of every link (accelerations are
/// left zero): what force elements that need the frames' motion read.
template <class S, class T, class X>
std::array<frame_kinematics<T>, S::tree.n_links> link_motion(const S& scene, const X& xf, const T* qd) {
  std::array<frame_kinematics<T>, S::tree.n_links> lk;
  for (auto& k : lk) {
    k.r = k.v = k.w = k.a = k.wd = Vec3<T>::Zero();
    k.R = Mat3<T>::Identity();
  }
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& xj = std::get<L - 1>(xf);
    const auto& P = lk[LI::parent];
    auto& c = lk[L];
    const Vec3<T> p = scene.model().set_offset[LI::parent_set].template cast<T>() + xj.p();
    if constexpr (LI::parent == 0) {
      // On the World: R_P = 1, r_P = ṙ_P = ω_P = 0.
      c.R = xj.matrix();
      c.r = p;
      if constexpr (XF::translates) c.v = xj.axis(qd[LI::q]);
      else c.v.setZero();
      if constexpr (XF::rotates) c.w = xj.axis(qd[LI::q]);
      else c.w.setZero();
    } else {
      Vec3<T> pv = P.w.cross(p);
      if constexpr (XF::translates) pv += xj.axis(qd[LI::q]);
      c.R = xj.matrix() * P.R;
      c.r = P.r + P.R.transpose() * p;
      c.v = P.v + P.R.transpose() * pv;
      c.w = xj.rot(P.w);
      if constexpr (XF::rotates) c.w += xj.axis(qd[LI::q]);
    }
  });
  return lk;
}

/// The external loads of the scene's force elements on each link, in link
/// coordinates: forces f_ext and torques n_ext about the link origin. Only the
/// links some element acts on (link_flags::has_ext, has_ext_f) are written.
/// A scene with only Torque elements needs the link rotations alone; one with
/// line or world forces first runs a position pass (link_motion).
template <class S, class T, class X, class NL>
void gather_external(const S& scene, const T& t, const joint_state<T>& x, const X& xf, NL& n_ext, NL& f_ext) {
  constexpr auto F = link_flags<S>::value;
  for (int L = 0; L < S::tree.n_links; ++L) {
    if (F.has_ext[L]) n_ext[L].setZero();
    if (F.has_ext_f[L]) f_ext[L].setZero();
  }
  if constexpr (has_motion_forces<S>()) {
    const auto lk = link_motion(scene, xf, x.qd_);
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force && force_acts<S, C>()) {
              constexpr int nf = int(Comp::frames.size());
              constexpr auto links = force_links<S, C>();
              std::array<frame_kinematics<T>, nf> fk;
              std::array<Vec3<T>, nf> p;
              for (int k = 0; k < nf; ++k) {
                const auto& L = lk[links[k]];
                p[k] = scene.model().set_offset[S::topology.set_of[S::table.frame_base[C] + k]].template cast<T>();
                if (links[k] == 0) {  // a frame on the World: at rest, unturned
                  fk[k].R.setIdentity();
                  fk[k].w.setZero();
                  fk[k].r = p[k];
                  fk[k].v.setZero();
                } else {
                  fk[k].R = L.R;
                  fk[k].w = L.w;
                  fk[k].r = L.r + L.R.transpose() * p[k];
                  fk[k].v = L.v + L.R.transpose() * L.w.cross(p[k]);
                }
              }
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
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force && force_acts<S, C>()) {
              constexpr auto links = force_links<S, C>();
              constexpr int la = links[0], lb = links[1];
              // Pure torque: M_ext acts on frame_b's side, −M_ext on frame_a's
              // (frames share their link's orientation: rigid edges only translate).
              const Vec3<T> M = scene.template component<C>().torque(t, x);
              if constexpr (lb != 0) {
                if constexpr (la == 0) n_ext[lb] += world_to_link<lb, S>(xf, M);
                else n_ext[lb] += world_to_link<lb, S>(xf, link_to_world<la, S>(xf, M));
              }
              if constexpr (la != 0) n_ext[la] -= M;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
  }
}

template <class T>
[[nodiscard]] std::string describe_state(const T* q, const T* qd, int n) {
  std::ostringstream os;
  os.precision(17);
  os << "q = [";
  for (int i = 0; i < n; ++i) os << (i ? ", " : "") << static_cast<long double>(q[i]);
  os << "], q̇ = [";
  for (int i = 0; i < n; ++i) os << (i ? ", " : "") << static_cast<long double>(qd[i]);
  os << "]";
  return os.str();
}

}  // namespace flange::detail
