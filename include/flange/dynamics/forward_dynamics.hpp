// The joint accelerations v̇ = M(q)⁻¹·(τ(t, q, v) − b(q, v)) at (t, q, v), in
// the algebra the scene's type calls for (algebra.hpp): planar arithmetic for
// a planar scene, spatial otherwise. b is the Newton–Euler bias
// (newton_euler.hpp), M the composite-rigid-body mass matrix
// (mass_matrix.hpp), τ the joints' own generalized forces (inputs and axis
// laws), and the solve an unrolled LDLᵀ with a relative pivot test (ldlt.hpp);
// where M is constant up to its joints' turns of their rates (model.hpp, folded_mass_matrix), its
// inverse folded at construction instead.
//
// accelerations_newton_euler and accelerations_planar force one algebra, for
// the tests that hold the two against each other.
#pragma once
#include "flange/scene/named_state.hpp"
#include "flange/detail/inline.hpp"
#include <array>
#include <cmath>
#include <string>

#include "flange/dynamics/external.hpp"
#include "flange/math/read_alone.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/loop_solve.hpp"
#include "flange/dynamics/mass_matrix.hpp"
#include "flange/dynamics/newton_euler.hpp"

namespace flange {

namespace detail {

/// Does any joint of the scene have a generalized force of its own (an input
/// or an axis law)? If none does, τ is zero by the scene's type and the
/// derivative computes −b directly.
template <class S>
constexpr bool has_joint_forces() {
  return []<int... L>(std::integer_sequence<int, L...>) {
    return (has_generalized_force<typename link_info<S, L + 1>::joint_type> || ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
}

/// The joints' own generalized forces (a Prismatic's force input, axis laws).
template <class S, class T>
void joint_forces(const S& scene, const T& t, const state_of<T> auto& x, T* tau) {
  for (int i = 0; i < S::n_v; ++i) tau[i] = T(0);
  for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    using LI = link_info<S, decltype(l)::value>;
    const auto& j = scene.template component<LI::joint>();
    if constexpr (has_generalized_force<typename LI::joint_type>)
      j.generalized_force(t, x, x.q_ + LI::q, x.v_ + LI::v, tau + LI::v);
  });
}

/// The joint owning rate v[i], and which of its rates it is.
template <class S>
constexpr std::pair<std::string_view, int> rate_owner(int i) {
  for (int c = 0; c < S::n_components; ++c)
    if (S::tree.v_offset[c] >= 0 && i >= S::tree.v_offset[c] && i < S::tree.v_offset[c] + S::table.nv[c])
      return {S::table.names[c], i - S::tree.v_offset[c]};
  return {"?", 0};
}

template <class S, class T>
[[noreturn, gnu::cold, gnu::noinline]] void singular_mass_matrix(const pivot_report<T>& p, const T& t, const T* q,
                                                                const T* v) {
  bool finite = true;
  for (int i = 0; i < S::n_q; ++i) finite = finite && std::isfinite(static_cast<double>(q[i]));
  for (int i = 0; i < S::n_v; ++i) finite = finite && std::isfinite(static_cast<double>(v[i]));
  if (!finite)  // a NaN state fails every pivot test; the true reason is the state
    throw simulation_error(concat("flange: the state is not finite at t = ", static_cast<double>(t), ", ",
                                  describe_state(q, S::n_q, v, S::n_v),
                                  ": the integration diverged before this evaluation (a step too large for the "
                                  "stepper's stability, or an input that returned NaN)"),
                           static_cast<double>(t), state_values(q, S::n_q, v, S::n_v), "the state is not finite");
  const double d = static_cast<double>(p.d), scale = static_cast<double>(p.scale);
  if (!std::isfinite(d) || !std::isfinite(scale))  // a finite state too large for its products (q² overflows)
    throw simulation_error(concat("flange: the state overflowed at t = ", static_cast<double>(t), ", ",
                                  describe_state(q, S::n_q, v, S::n_v),
                                  ": it is finite, but too large for the dynamics' products in double (the mass "
                                  "matrix's pivot came out ", d, "): the integration diverged before this "
                                  "evaluation (a step too large for the stepper's stability)"),
                           static_cast<double>(t), state_values(q, S::n_q, v, S::n_v), "the state overflowed");
  const auto [joint, k] = rate_owner<S>(p.index);
  const std::string why =
      scale > 0 ? concat("its pivot ", d, " is ", d / scale, " of the inertia it moves (", scale,
                         "), at or below the relative tolerance ", pivot_tolerance<S::n_v, T>(),
                         ": its axis passes through all the mass it moves, or its motion repeats other joints'")
                : std::string("it moves nothing with mass or inertia");
  const std::string which = S::table.nv[S::index_of(joint)] > 1 ? concat(", its rate ", k) : std::string();
  throw simulation_error(concat("flange: singular mass matrix at t = ", static_cast<double>(t), ", ",
                                describe_state(q, S::n_q, v, S::n_v), ": joint \"", joint, "\"", which, " (v[",
                                p.index, "]): ", why),
                         static_cast<double>(t), state_values(q, S::n_q, v, S::n_v),
                         concat("singular mass matrix: joint \"", joint, "\"", which, ": ", why));
}

/// The link motions an algebra's passes need at q (a tuple, links.hpp), and
/// the spatial ones the force elements' pose pass needs: the same tuple in
/// the spatial algebra, a second one only for a planar scene with line or
/// world forces.
template <class S>
constexpr bool needs_poses() {
  return has_motion_forces<S>() || has_loops<S>;
}
template <class A, class S, class T>
[[gnu::always_inline]] inline auto algebra_motions(const S& scene, const T* q) {
  return link_motions<A, T, needs_poses<S>()>(scene, q);
}
template <class A, class S, class T, class M>
[[gnu::always_inline]] inline decltype(auto) pose_motions(const S& scene, const T*, const M& motions) {
  if constexpr (A::planar && needs_poses<S>()) return spatial_offsets<T>(scene, motions);
  else return (motions);
}

/// A scene's M at q as its loops' solve used it: its LDLᵀ factor in place
/// (ldlt_factor), and the factor's pivots.
template <class S, class T>
struct factored_mass {
  Eigen::Matrix<T, S::n_v, S::n_v> M;
  ldlt_pivots<S::n_v, T> f;
};

/// v̇ = M⁻¹·(τ − b) with the motions at q given (and, for a scene with
/// loops, M's factor into *mass where given). Always inlined into its
/// caller: a call would pass every link's motion through memory.
template <class A, class S, class T, class M, class PM>
[[gnu::always_inline]] inline void solve_accelerations(const S& scene, const T& t, const T* q, const T* v, T* vdot,
                                                      const M& motions, const PM& pose, T* lambda = nullptr,
                                                      bool* exact = nullptr, factored_mass<S, T>* mass = nullptr) {
  constexpr int N = S::n_v;
  const auto x = state_view(scene, q, v);
  link_loads<S, T> n_ext, f_ext;
  gather_external<A>(scene, t, x, motions, pose, n_ext, f_ext);
  std::array<T, N> b, r;
  inverse_dynamics<A>(scene, motions, v, no_rates{}, n_ext, f_ext, b.data());
  // Where M is folded, the product by its inverse follows at once: b, which
  // the passes have just stored entry by entry, is read a scalar at a time
  // (math/read_alone.hpp; a free body 29 ns against 32 with the packed
  // copy). Elsewhere the packed copy measured faster (a chain of six 129
  // against 136 ns).
  constexpr bool alone = folded_mass_matrix<S>();
  const auto b_at = [&](int i) FLANGE_INLINE_LAMBDA {
    if constexpr (alone) return flange::read_alone(b[i]);
    else return b[i];
  };
  if constexpr (has_joint_forces<S>()) {
    std::array<T, N> tau;
    joint_forces(scene, t, x, tau.data());
    for (int i = 0; i < N; ++i) r[i] = tau[i] - b_at(i);
  } else {
    for (int i = 0; i < N; ++i) r[i] = -b_at(i);
  }
  if constexpr (folded_mass_matrix<S>() && epsilon<T>() >= epsilon<double>()) {
    // M is constant up to its joints' turns of their rates: v̇ = M⁻¹·r with
    // M⁻¹ folded at construction, block by block (model.hpp), and a turned
    // block's rates turned in and back, Tᵀ·M₀⁻¹·T·r. No mass-matrix pass, no
    // division. (Folded in double: a wider scalar, long double, forms and
    // solves M itself.)
    const auto& m = scene.model();
    if (m.mass_pivot.index >= 0) [[unlikely]]
      singular_mass_matrix<S>(pivot_report<T>{m.mass_pivot.index, T(m.mass_pivot.d), T(m.mass_pivot.scale)}, t, q, v);
    for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      constexpr int o = folded_mass_offset<S, L>();
      const auto times_inverse = [&](const T* in, T* out) FLANGE_INLINE_LAMBDA {
        for (int i = 0; i < LI::nv; ++i) {
          T a = T(m.inverse_mass[o + i * LI::nv]) * in[0];
          for (int j = 1; j < LI::nv; ++j) a += T(m.inverse_mass[o + i * LI::nv + j]) * in[j];
          out[i] = a;
        }
      };
      if constexpr (turned_subspace<typename LI::joint_type>) {
        const auto& mo = std::get<L - 1>(motions);
        std::array<T, LI::nv> rl, al;
        mo.turn_rates(r.data() + LI::v, rl.data());
        times_inverse(rl.data(), al.data());
        mo.unturn_rates(al.data(), vdot + LI::v);
      } else {
        times_inverse(r.data() + LI::v, vdot + LI::v);
      }
    });
  } else {
    Eigen::Matrix<T, N, N> Mm;
    std::array<T, N> scale;
    mass_matrix<A>(scene, motions, Mm, scale.data());
    if constexpr (has_loops<S>) {
      ldlt_pivots<N, T> f;
      if (const auto pivot = ldlt_factor<N>(Mm, f, scale.data(), mass_factor<S>{}); pivot.index >= 0) [[unlikely]]
        singular_mass_matrix<S>(pivot, t, q, v);
      constrained_accelerations(scene, pose, Mm, f, v, r.data(), vdot, lambda, exact);
      if (mass) {
        mass->M = Mm;
        mass->f = f;
      }
    } else {
      if (const auto pivot = solve_spd<N>(Mm, r.data(), vdot, scale.data(), mass_factor<S>{}); pivot.index >= 0)
          [[unlikely]]
        singular_mass_matrix<S>(pivot, t, q, v);
    }
  }
}

/// v̇ at (t, q, v) in algebra A, compiled into the caller (algorithm.hpp's
/// accelerations() for a small scene).
template <class A, class S, class T>
FLANGE_INLINE void accelerations_inline(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  const auto motions = algebra_motions<A>(scene, q);
  solve_accelerations<A>(scene, t, q, v, vdot, motions, pose_motions<A>(scene, q, motions));
}

}  // namespace detail

/// v̇ at (t, q, v) in algebra A. Throws simulation_error if M is singular.
template <class A, class S, class T>
void accelerations_in(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  // The body of accelerations_inline, not a call to it: GCC compiles the
  // always-inline form longer into this function.
  const auto motions = detail::algebra_motions<A>(scene, q);
  detail::solve_accelerations<A>(scene, t, q, v, vdot, motions, detail::pose_motions<A>(scene, q, motions));
}

/// v̇ at (t, q, v) and the loops' constraint forces λ (dynamics/loop_solve.hpp),
/// for a scene with loops; with exact given, whether the loop solve was the
/// exact one there (constrained_accelerations); with mass given, the
/// factored M it solved with (what simulate/jacobian.hpp's implicit
/// differentiation solves with too).
template <class S, class T>
void accelerations_and_constraint_forces(const S& scene, const T& t, const T* q, const T* v, T* vdot, T* lambda,
                                         bool* exact = nullptr, detail::factored_mass<S, T>* mass = nullptr) {
  using A = algebra_t<S>;
  const auto motions = detail::algebra_motions<A>(scene, q);
  detail::solve_accelerations<A>(scene, t, q, v, vdot, motions, detail::pose_motions<A>(scene, q, motions), lambda,
                                 exact, mass);
}

/// v̇ at (t, q, v) by Newton–Euler, the mass matrix and LDLᵀ, in the
/// algebra the scene's type calls for. accelerations() (algorithm.hpp) picks
/// this or the articulated-body algorithm.
template <class S, class T>
void accelerations_mass_matrix(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  accelerations_in<algebra_t<S>>(scene, t, q, v, vdot);
}
/// The same in spatial arithmetic, whatever the scene.
template <class S, class T>
void accelerations_newton_euler(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  accelerations_in<spatial_algebra>(scene, t, q, v, vdot);
}
/// The same in planar arithmetic (for a planar scene only).
template <class S, class T>
void accelerations_planar(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  static_assert(detail::planar_axis<S>() >= 0, "flange: accelerations_planar needs a planar scene (dynamics/algebra.hpp)");
  accelerations_in<planar_algebra<detail::planar_axis<S>()>>(scene, t, q, v, vdot);
}

/// The mass matrix M(q), n_v × n_v (spatial arithmetic).
template <class S, class T>
Eigen::Matrix<T, S::n_v, S::n_v> mass_matrix(const S& scene, const T* q) {
  const auto motions = detail::link_motions<spatial_algebra, T, true>(scene, q);
  Eigen::Matrix<T, S::n_v, S::n_v> M;
  std::array<T, S::n_v> scale;
  detail::mass_matrix<spatial_algebra>(scene, motions, M, scale.data());
  return M;
}

/// τ = ID(q, v, v̇): the generalized forces for accelerations vdot (spatial
/// arithmetic), with gravity and the force elements' loads but without the
/// joints' own forces.
template <class S, class T>
std::array<T, S::n_v> inverse_dynamics(const S& scene, const T& t, const T* q, const T* v, const T* vdot) {
  using namespace detail;
  const auto x = state_view(scene, q, v);
  std::array<T, S::n_v> tau;
  const auto motions = link_motions<spatial_algebra, T, true>(scene, q);
  link_loads<S, T> n_ext, f_ext;
  gather_external<spatial_algebra>(scene, t, x, motions, motions, n_ext, f_ext);
  detail::inverse_dynamics<spatial_algebra>(scene, motions, v, vdot, n_ext, f_ext, tau.data());
  return tau;
}

}  // namespace flange
