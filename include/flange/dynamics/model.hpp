// What the recursive algorithms precompute at scene construction: every
// connection set's pose relative to its link's origin (rigid edges folded:
// FixedTranslation's offset, FixedRotation's rotation), and every link's
// rigid-body inertia (all the bodies that move with it), and, where the
// scene's type shows the mass matrix is constant up to its joints' turns of
// their rates (folded_mass_matrix), its inverse. These are constants of the
// scene, so the derivative never recomputes them.
#pragma once
#include "flange/detail/inline.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/dynamics/axis_frames.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/math/rotation.hpp"

namespace flange::detail {

/// Mass m, first moment h = m·c and inertia I about the link origin, all in
/// link coordinates.
template <class T>
struct rigid_inertia {
  T m{0};
  Vec3<T> h = Vec3<T>::Zero();
  Mat3<T> I = Mat3<T>::Zero();

  /// Adds `o`, given in a frame whose origin is at p (no rotation). With
  /// ã·b̃ = b·a' − (a·b)·1 the parallel-axis shift
  ///   I += I_o − m·p̃² − p̃·h̃ − h̃·p̃
  /// becomes (m|p|² + 2 p·h)·1 − m·p·p' − h·p' − p·h': outer products, no 3×3 products.
  void add_shifted(const rigid_inertia& o, const Vec3<T>& p) {
    // Written out by entry: the outer products as Eigen expressions cost a
    // small unit about a fifth of a second to compile, for 27 multiplications.
    const T mp[3] = {o.m * p[0], o.m * p[1], o.m * p[2]};
    const T diag = mp[0] * p[0] + mp[1] * p[1] + mp[2] * p[2] + T(2) * (p[0] * o.h[0] + p[1] * o.h[1] + p[2] * o.h[2]);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) I(i, j) += o.I(i, j) - (mp[i] + o.h[i]) * p[j] - p[i] * o.h[j];
      I(i, i) += diag;
    }
    for (int i = 0; i < 3; ++i) h[i] += o.h[i] + mp[i];
    m += o.m;
  }
};

/// Whether the scene's tree is one the dynamics can walk (no loop, nothing floating).
template <class S>
inline constexpr bool walkable = S::topology.ok() && S::tree.loop < 0 && S::tree.floating < 0;

/// A joint whose motion subspace, in its link's coordinates, is the same at
/// every q (core/joint.hpp: the optional member fixed_subspace).
template <class J>
inline constexpr bool fixed_subspace = requires {
  requires J::fixed_subspace;
};

/// A joint whose motion subspace is a constant one turned by an orthogonal
/// T(q) on its rates, S(q) = S₀·T(q) (core/joint.hpp: turned_subspace): a
/// FreeMotion, whose linear rates are in frame_a's coordinates.
template <class J>
inline constexpr bool turned_subspace = requires {
  requires J::turned_subspace;
};

/// Is M(q) constant but for its joints' turns of their rates? It is when
/// every joint hangs from the root link (no joint moves another, and no loop
/// is cut) and every joint's motion subspace is fixed in its link or turned
/// (above): M is then block diagonal, each block Sᵀ·I·S of one link's own
/// inertia, constant, or Tᵀ·M₀·T with M₀ its value at T = 1. The paper's
/// robot arm is one, and so is a scene of free bodies. Such an M is inverted
/// once, at construction (fold_mass_matrix, mass_matrix.hpp, at the neutral
/// configuration, where every T is 1), and the derivative multiplies by the
/// inverse, M⁻¹ = Tᵀ·M₀⁻¹·T block by block.
template <class S>
constexpr bool folded_mass_matrix() {
  if constexpr (!walkable<S> || S::tree.n_cuts > 0 || S::tree.n_links < 2) {
    return false;
  } else {
    return []<int... L>(std::integer_sequence<int, L...>) {
      return ((S::tree.link_parent[L + 1] == 0 &&
               (fixed_subspace<typename S::template component_type<S::tree.link_joint[L + 1]>> ||
                turned_subspace<typename S::template component_type<S::tree.link_joint[L + 1]>>)) &&
              ...);
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  }
}

/// Where link L's block of a folded M⁻¹ starts (row-major nv × nv blocks,
/// links in order); at L = n_links, the storage they need.
template <class S, int L>
constexpr int folded_mass_offset() {
  int n = 0;
  for (int l = 1; l < L; ++l) n += S::table.nv[S::tree.link_joint[l]] * S::table.nv[S::tree.link_joint[l]];
  return n;
}

struct no_folded_mass {};
struct no_link_turn {};
struct no_gravity {};

template <int NL, int NS, int NB = 0, bool Turned = false, bool Gravity = false>
struct dynamics_model {
  /// −g, the World's acceleration in the recursive passes (kinematics.hpp),
  /// kept negated so that no pass negates it at every evaluation. Not kept by
  /// a scene without gravity.
  [[no_unique_address]] std::conditional_t<Gravity, Vec3d, no_gravity> minus_g{};
  std::array<Vec3d, NS> set_offset{};    ///< a set's origin in its link's coordinates
  /// The scene's size: the largest |set_offset| (1 m without one), the
  /// loops' yardstick for lengths (loop_solve.hpp).
  double length = 1.0;
  std::array<Mat3d, NS> set_rotation{};  ///< rotates link coordinates into the set's
  std::array<rigid_inertia<double>, NL> link{};
  /// C_L = A_L·R_s of a link that computes in its joint's axis frame
  /// (axis_frames.hpp): its motion is E = R_z(q)·C_L. Not kept by a scene
  /// without such links.
  [[no_unique_address]] std::conditional_t<Turned, std::array<Mat3d, NL>, no_link_turn> link_turn{};
  /// The same for an aligned link, as R_z(θ₀)·R_x(α).
  [[no_unique_address]] std::conditional_t<Turned, std::array<axis_alignment, NL>, no_link_turn> link_align{};
  /// A folded M's inverse, link by link (its diagonal blocks, at T = 1), and its
  /// failed pivot if it is singular: the derivative reports that with the
  /// time and state of the call, as for any singular M.
  [[no_unique_address]] std::conditional_t<NB == 0, no_folded_mass, std::array<double, NB>> inverse_mass{};
  [[no_unique_address]] std::conditional_t<NB == 0, no_folded_mass, pivot_report<double>> mass_pivot{};
};

/// Whether scene S has gravity; false, not a second error, for a scene
/// without a World (the scene reports that one itself).
template <class S>
constexpr bool gravity_in_model() {
  if constexpr (S::topology.world < 0) return false;
  else return S::has_gravity;
}

/// The model of scene S.
template <class S>
using model_for = dynamics_model<S::tree.n_links, (S::topology.n_sets == 0 ? 1 : S::topology.n_sets),
                                 folded_mass_matrix<S>() ? folded_mass_offset<S, S::tree.n_links>() : 0,
                                 axis_frames<S>::any, gravity_in_model<S>()>;

template <class S, class F>
void for_each_component(const S& scene, F&& f) {
  [&]<int... I>(std::integer_sequence<int, I...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, I>{}, scene.template component<I>()), ...);
  }(std::make_integer_sequence<int, S::n_components>{});
}

/// Calls f(component) for the component with run-time index c. In a scene
/// of more than 16 components, through a table with one small function per
/// component, so that the set-up loops over sets do not unroll f for every
/// component at every call; a small scene keeps the comparisons, which
/// inline f and cost less than the indirect call (`recover` of the arm).
template <class S, class F>
void visit_component(const S& scene, int c, F&& f) {
  if constexpr (S::n_components <= 16) {
    for_each_component(scene, [&](auto i, const auto& comp) FLANGE_INLINE_LAMBDA {
      if (decltype(i)::value == c) f(comp);
    });
  } else {
    using entry = void (*)(const S&, F&);
    static constexpr auto table = []<int... I>(std::integer_sequence<int, I...>) {
      return std::array<entry, S::n_components>{+[](const S& s, F& g) { g(s.template component<I>()); }...};
    }(std::make_integer_sequence<int, S::n_components>{});
    table[c](scene, f);
  }
}

/// The name and type name of component c, for a message.
template <class S>
std::string describe_component(const S&, int c) {
  return concat(S::table.type_names[c], " \"", S::table.names[c], "\"");
}

/// The axis frames (axis_frames.hpp), once the sets' poses in their links'
/// own coordinates are known: each turned link's A_L (x normal to its aligned
/// child's axis), every set of it turned by A_L, and each turned link's C_L,
/// for an aligned one as (α, θ₀).
template <class S, class Model>
void turn_to_axis_frames(const S& scene, Model& model) {
  constexpr auto& tree = S::tree;
  constexpr auto& frames = axis_frames<S>::turned;
  constexpr auto& aligned = axis_frames<S>::aligned;
  std::array<Vec3d, tree.n_links> n;
  for (int L = 1; L < tree.n_links; ++L)
    if (frames[L])
      visit_component(scene, tree.link_joint[L], [&](const auto& j) FLANGE_INLINE_LAMBDA {
        if constexpr (axis_framed_joint<std::remove_cvref_t<decltype(j)>>) n[L] = j.n();
      });
  std::array<Mat3d, tree.n_links> A;
  for (int L = 1; L < tree.n_links; ++L) {
    if (!frames[L]) continue;
    Vec3d m = Vec3d::Zero();  // the aligned child's axis in L's coordinates
    for (int C = L + 1; C < tree.n_links; ++C)
      if (aligned[C] && tree.link_parent[C] == L) m = model.set_rotation[tree.link_parent_set[C]].transpose() * n[C];
    A[L] = axis_frame_rotation(n[L], m);
  }
  for (int s = 0; s < int(model.set_rotation.size()); ++s) {
    const int L = tree.set_link[s];
    if (L <= 0 || !frames[L]) continue;
    model.set_rotation[s] = model.set_rotation[s] * A[L].transpose();
    model.set_offset[s] = A[L] * model.set_offset[s];
  }
  for (int L = 1; L < tree.n_links; ++L) {
    if (!frames[L]) continue;
    const Mat3d C = A[L] * model.set_rotation[tree.link_parent_set[L]];
    model.link_turn[L] = C;
    if (aligned[L]) {
      // C's last row is (0, −sin α, cos α) (x of the parent is normal to
      // this axis); C·R_x(α)ᵀ is then R_z(θ₀).
      auto& a = model.link_align[L];
      const double r = std::hypot(C(2, 1), C(2, 2));
      a.c = C(2, 2) / r;
      a.s = -C(2, 1) / r;
      const Mat3d Rx = to_matrix<double>(coordinate_rotation<double, 0>{a.c, a.s});
      const Mat3d Z = C * Rx.transpose();
      a.offset = std::atan2(Z(0, 1), Z(0, 0));
    }
  }
}

// The scene-independent arithmetic and messages of build_model, as plain
// functions out of line: compiled once per unit and called, not copied into
// each component's branch of the scene's construction.

/// Set s's pose from its parent set's (Rp, pp) through a rigid edge whose
/// frame_b sits at x in its frame_a, walked forwards (from frame_a) or back.
FLANGE_LAZY
[[gnu::noinline]] void place_set(Mat3d& R, Vec3d& p, const Mat3d& Rp, const Vec3d& pp, const pose<double>& x,
                                 bool forward) {
  if (forward) {
    R = x.R * Rp;
    p = pp + Rp.transpose() * x.p;
  } else {
    R = x.R.transpose() * Rp;
    p = pp - Rp.transpose() * (x.R * x.p);
  }
}
FLANGE_COMMON(void place_set<0>(Mat3d&, Vec3d&, const Mat3d&, const Vec3d&, const pose<double>&, bool))
FLANGE_LAZY
[[noreturn, gnu::cold]] void frame_overflows(const std::string& who, const Vec3d& p, double mass_scale) {
  throw parameter_error(concat(who, ": it places a frame at [", p, "] m from its link's origin, where mass times "
                               "length squared (", mass_scale, " kg · |p|²) overflows the dynamics; rescale the "
                               "scene's units"));
}
FLANGE_COMMON(void frame_overflows<0>(const std::string&, const Vec3d&, double))
FLANGE_LAZY
[[noreturn, gnu::cold]] void total_mass_overflows(const std::string& who, double m) {
  throw parameter_error(concat(who, ": mass m = ", m, " makes the scene's total mass overflow"));
}
FLANGE_COMMON(void total_mass_overflows<0>(const std::string&, double))
/// Adds a body (mass m, centre of mass r_cm and inertia J about its frame,
/// in the frame's coordinates) whose frame sits at p, turned by R, in its
/// link; throws naming the body when the sum overflows.
FLANGE_LAZY
[[gnu::noinline]] void add_body(rigid_inertia<double>& link, const Mat3d& R, const Vec3d& p, double m,
                                const Vec3d& r_cm, const Mat3d& J, std::string_view type, std::string_view name) {
  rigid_inertia<double> b;
  b.m = m;
  b.h = R.transpose() * (m * r_cm);
  b.I = R.transpose() * J * R;
  link.add_shifted(b, p);
  if (!(std::isfinite(link.m) && all_finite(link.h) && all_finite(link.I)))
    throw parameter_error(concat(type, " \"", name, "\": its mass ", m, " kg at [", p + R.transpose() * r_cm,
                                 "] m from its link's origin gives an inertia that overflows; rescale the scene's "
                                 "units"));
}
FLANGE_COMMON(void add_body<0>(rigid_inertia<double>&, const Mat3d&, const Vec3d&, double, const Vec3d&,
                              const Mat3d&, std::string_view, std::string_view))

template <class S>
auto build_model(const S& scene) {
  constexpr auto& tree = S::tree;
  constexpr auto& topo = S::topology;
  model_for<S> model{};
  model.set_offset.fill(Vec3d::Zero());  // Eigen leaves its vectors uninitialised
  model.set_rotation.fill(Mat3d::Identity());
  if constexpr (gravity_in_model<S>()) model.minus_g = -scene.gravity();
  if constexpr (walkable<S>) {
    // The whole mass, the yardstick for lengths: m·|p|² must stay finite.
    double total_mass = 0;
    for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
      if constexpr (carries_body<std::remove_cvref_t<decltype(c)>>) {
        total_mass += c.m();
        if (!std::isfinite(total_mass)) total_mass_overflows(describe_component(scene, decltype(i)::value), c.m());
      }
    });
    const double mass_scale = std::max(1.0, total_mass);
    // Sets in breadth-first order: a set's parent is placed before it. A rigid
    // edge gives frame_b's pose in frame_a; walked from frame_b, its inverse.
    for (int i = 0; i < tree.n_tree_sets; ++i) {
      const int s = tree.set_order[i];
      const int ps = tree.set_parent[s];
      if (ps < 0) continue;
      visit_component(scene, tree.set_edge[s], [&](const auto& e) FLANGE_INLINE_LAMBDA {
        if constexpr (std::remove_cvref_t<decltype(e)>::kind == role::rigid)
          place_set(model.set_rotation[s], model.set_offset[s], model.set_rotation[ps], model.set_offset[ps],
                    e.template relative_pose<double>(), tree.set_edge_dir[s] > 0);
      });
      const Vec3d& p = model.set_offset[s];
      if (!std::isfinite(mass_scale * (p(0) * p(0) + p(1) * p(1) + p(2) * p(2))))
        frame_overflows(describe_component(scene, tree.set_edge[s]), p, mass_scale);
    }
    if constexpr (axis_frames<S>::any) turn_to_axis_frames(scene, model);
    double L = 0;
    for (const auto& o : model.set_offset) L = std::max(L, o.norm());
    if (L > 0) model.length = L;
    for_each_component(scene, [&](auto i, const auto& c) FLANGE_INLINE_LAMBDA {
      using C = std::remove_cvref_t<decltype(c)>;
      if constexpr (carries_body<C>) {
        const int s = topo.set_of[S::table.frame_base[decltype(i)::value]];
        if (tree.set_link[s] < 0) return;
        // The body's mass, first moment and inertia about frame_a, in the
        // set's coordinates, turned into its link's coordinates.
        add_body(model.link[tree.set_link[s]], model.set_rotation[s], model.set_offset[s], c.m(), c.r_cm(),
                 c.inertia_about_frame(), C::type_name, C::name.view());
      }
    });
  }
  return model;
}

}  // namespace flange::detail
