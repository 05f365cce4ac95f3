// Compile-time facts about one link of the kinematic tree, and the loops over
// links that the compiler unrolls (parents before children, or the reverse).
#pragma once
#include <tuple>
#include <utility>

#include "flange/dynamics/joint_transform.hpp"
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
    std::array<bool, NL> has_ext{};   ///< a force element acts on the link
    std::array<bool, NL> need_f{};    ///< the link force f is used (prismatic joint, or passed to a parent)
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
            if constexpr (S::template component_type<C>::kind == role::force) {
              const int la = S::tree.set_link[S::topology.set_of[S::table.frame_base[C]]];
              const int lb = S::tree.set_link[S::topology.set_of[S::table.frame_base[C] + 1]];
              if (la != lb) t.has_ext[la] = t.has_ext[lb] = true;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
    return t;
  }();
};

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

/// The torques of the scene's force elements on each link, in link
/// coordinates; only the links some element acts on (link_flags::has_ext) are written.
template <class S, class T, class X, class NL>
void gather_external(const S& scene, const T& t, const joint_state<T>& x, const X& xf, NL& n_ext) {
  for (int L = 0; L < S::tree.n_links; ++L)
    if (link_flags<S>::value.has_ext[L]) n_ext[L].setZero();
  [&]<int... C>(std::integer_sequence<int, C...>) {
    (
        [&] {
          using Comp = typename S::template component_type<C>;
          if constexpr (Comp::kind == role::force) {
            constexpr int la = S::tree.set_link[S::topology.set_of[S::table.frame_base[C]]];
            constexpr int lb = S::tree.set_link[S::topology.set_of[S::table.frame_base[C] + 1]];
            if constexpr (la != lb) {
              // Pure torque: M_ext acts on frame_b's side, −M_ext on frame_a's
              // (frames share their link's orientation: rigid edges only translate).
              const Vec3<T> M = scene.template component<C>().torque(t, x);
              if constexpr (lb != 0) {
                if constexpr (la == 0) n_ext[lb] += world_to_link<lb, S>(xf, M);
                else n_ext[lb] += world_to_link<lb, S>(xf, link_to_world<la, S>(xf, M));
              }
              if constexpr (la != 0) n_ext[la] -= M;
            }
          }
        }(),
        ...);
  }(std::make_integer_sequence<int, S::n_components>{});
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
