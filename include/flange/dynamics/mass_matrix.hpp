// The joint-space mass matrix M(q) by the composite-rigid-body algorithm.
//
// Coming up the tree (a walk, kinematics.hpp) each link returns the inertia
// of its whole subtree about its origin, link coordinates: its own plus each
// child's turned into its coordinates and shifted to its origin,
//
//   m += m_C,  h += Eᵀ·h_C + m_C·p,
//   I += Eᵀ·I_C·E + (m_C·|p|² + 2·p·h')·1 − m_C·p·pᵀ − h'·pᵀ − p·h'ᵀ   (h' = Eᵀ·h_C)
//
// For each column k of its motion subspace the force F = I_c·S_k (n = I·ω_k
// + h × v_k, f = m·v_k + ω_k × h) gives M's entries at its own joint (Sᵀ·F)
// and, carried up through the ancestors, at theirs. Entries between two
// branches are zero and are written as such (branch_pairs). In the planar
// algebra the composite inertia is m, the in-plane first moment and I_KK.
#pragma once
#include <algorithm>
#include <array>

#include "flange/detail/inline.hpp"

#include "flange/dynamics/kinematics.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/math/congruence.hpp"
#include "flange/dynamics/newton_euler.hpp"

namespace flange::detail {

/// The pairs of joint rates on different branches: neither link is an
/// ancestor of the other, so their mass-matrix entries are zero (none for a
/// chain). The walk writes only ancestor pairs; these are the rest.
template <class S>
constexpr auto branch_pairs() {
  constexpr auto& tree = S::tree;
  constexpr int NL = tree.n_links;
  auto related = [](int a, int b) FLANGE_INLINE_LAMBDA {
    for (int x = b; x > 0; x = tree.link_parent[x])
      if (x == a) return true;
    return false;
  };
  constexpr int count = [&]() FLANGE_INLINE_LAMBDA {
    int n = 0;
    for (int a = 1; a < NL; ++a)
      for (int b = a + 1; b < NL; ++b)
        if (!related(a, b))
          n += S::table.nv[tree.link_joint[a]] * S::table.nv[tree.link_joint[b]];
    return n;
  }();
  std::array<std::pair<int, int>, count> pairs{};
  int k = 0;
  for (int a = 1; a < NL; ++a)
    for (int b = a + 1; b < NL; ++b)
      if (!related(a, b)) {
        const int ja = tree.link_joint[a], jb = tree.link_joint[b];
        for (int i = 0; i < S::table.nv[ja]; ++i)
          for (int j = 0; j < S::table.nv[jb]; ++j) pairs[k++] = {tree.v_offset[ja] + i, tree.v_offset[jb] + j};
      }
  return pairs;
}

/// The entries of M that can be nonzero: those between the rates of one
/// link and of its ancestors (branch_pairs' complement).
template <class S>
struct mass_sparsity {
  static constexpr sparsity<S::n_v> matrix() {
    sparsity<S::n_v> p;
    for (int i = 0; i < S::n_v; ++i)
      for (int j = 0; j < i; ++j) p.nz[i][j] = true;
    for (const auto& [i, j] : branch_pairs<S>()) p.nz[std::max(i, j)][std::min(i, j)] = false;
    return p;
  }
};
/// The LDLᵀ factor of M as far as its entries can be nonzero (ldlt.hpp):
/// sparse for a tree whose branches leave most of M zero.
template <class S>
using mass_factor = sparse_factor<mass_sparsity<S>, S::n_v>;

/// A subtree's inertia in the composite types of algebra A (algebra.hpp).
template <class A, class T>
struct composite_inertia {
  using types = composite_types<A, T>;
  T m;
  typename types::h h;
  typename types::I I_o;
};

template <class A, class T, class H, class I>
FLANGE_INLINE composite_inertia<A, T> widen(const rigid_view<T, H, I>& own) {
  composite_inertia<A, T> c;
  c.m = own.m;
  c.h = widen_to<A::linear_mask>(own.h);
  if constexpr (A::planar) {
    c.I_o.d[A::normal] = value_of<T>(trace(own.I_o));
  } else {
    c.I_o = to_matrix<T>(own.I_o);
  }
  return c;
}

/// acc += the child's subtree inertia c (child coordinates) carried to the
/// parent through the child's motion m.
template <class A, class T, class M, class C>
FLANGE_INLINE void add_child(composite_inertia<A, T>& acc, const M& m, const C& c) {
  const auto h = rot_t(m.E(), c.h);
  acc.m += c.m;
  acc.h = acc.h + h;
  if constexpr (A::planar) {
    acc.I_o.d[A::normal] += value_of<T>(trace(c.I_o));
  } else {
    acc.I_o += rotated_back_sym_by_columns<T>(m.E(), to_matrix<T>(c.I_o));
  }
  if constexpr (!is_zero_vec<decltype(m.p)>) {
    acc.h = acc.h + c.m * m.p;
    const T shift = value_of<T>(c.m * dot(m.p, m.p) + T(2) * value_of<T>(dot(m.p, h)));
    if constexpr (A::planar) {
      acc.I_o.d[A::normal] += shift;  // p and h lie in the plane: the outer products have no KK entry
    } else {
      const Vec3<T> p = m.p.dense(), hd = h.dense();
      acc.I_o -= (c.m * p + hd) * p.transpose() + p * hd.transpose();
      acc.I_o.diagonal().array() += shift;
    }
  }
}

/// The yardstick of the relative pivot test for a column: what its diagonal
/// entry would be before projection (trace of the rotational inertia for a
/// turning column, the mass for a sliding one).
template <class T, class I_, class Mot>
FLANGE_INLINE T column_scale(const I_& c, const Mot& s) {
  constexpr bool ang = !is_zero_vec<decltype(s.ang)>, lin = !is_zero_vec<decltype(s.lin)>;
  if constexpr (ang && lin) return value_of<T>(trace(c.I_o)) + c.m;
  else if constexpr (ang) return value_of<T>(trace(c.I_o));
  else return c.m;
}

/// The composite-rigid-body pass as a walk.
template <class A, class S, class T, class Motions, class MM>
struct mass_matrix_pass {
  const S& scene;
  const Motions& motions;
  MM& M;
  T* scale;

  template <int L, class D>
  FLANGE_INLINE auto at(const D&) {
    if constexpr (L == 0) {
      return nothing{};
    } else {
      const auto own = link_inertia<A, T, L>(scene);
      if constexpr (children<S, L>().size() == 0) return own;  // a leaf: its own, typed
      else return widen<A>(own);
    }
  }
  template <int, int>
  FLANGE_INLINE nothing down(nothing) {
    return {};
  }
  template <int L, int C, class I_, class IC>
  FLANGE_INLINE I_ gather(I_ acc, const IC& child) {
    if constexpr (L != 0) add_child(acc, std::get<C - 1>(motions), child);
    return acc;
  }
  /// Carries the force F of link L's column j up from link J, writing M's
  /// entries at each ancestor's joint.
  template <int L, int J, class W>
  FLANGE_INLINE void carry(const W& F, int j) {
    constexpr int P = link_info<S, J>::parent;
    if constexpr (P != 0) {
      const auto Fp = carry_up(std::get<J - 1>(motions), F);
      const auto g = std::get<P - 1>(motions).project(Fp.n, Fp.f);
      for (int i = 0; i < link_info<S, P>::nv; ++i) M(link_info<S, P>::v + i, j) = M(j, link_info<S, P>::v + i) = g[i];
      carry<L, P>(Fp, j);
    }
  }
  template <int L, class I_>
  FLANGE_INLINE I_ leave(nothing, I_ c) {
    if constexpr (L != 0) {
      using LI = link_info<S, L>;
      const auto& m = std::get<L - 1>(motions);
      [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
        (
            [&]() FLANGE_INLINE_LAMBDA {
              const auto s = m.template col<K>();
              const auto F = inertia_times(c, s);
              const auto g = m.project(F.n, F.f);
              constexpr int j = LI::v + K;
              for (int i = 0; i <= K; ++i) M(LI::v + i, j) = M(j, LI::v + i) = g[i];
              scale[j] = column_scale<T>(c, s);
              carry<L, L>(F, j);
            }(),
            ...);
      }(std::make_integer_sequence<int, LI::nv>{});
    }
    return c;
  }
};

/// M(q) into M (n_v × n_v), and each column's pivot yardstick into scale.
template <class A, class S, class T, class Motions, class MM>
FLANGE_INLINE void mass_matrix(const S& scene, const Motions& motions, MM& M, T* scale) {
  constexpr auto pairs = branch_pairs<S>();
  // Where most of M is zero between branches, zeroing it whole is faster
  // than entry by entry (the pass assigns the rest).
  if constexpr (requires { M.setZero(); } && 4 * pairs.size() > std::size_t(S::n_v * S::n_v)) M.setZero();
  else
    for (const auto& [i, j] : pairs) M(i, j) = M(j, i) = T(0);
  mass_matrix_pass<A, S, T, Motions, MM> ctx{scene, motions, M, scale};
  walk<S, 0>(ctx, nothing{});
}

/// Folds M (folded_mass_matrix, model.hpp) into the model at construction:
/// M from this pass at the neutral configuration (where every joint's turn
/// of its rates is 1; for a fixed subspace any configuration would do),
/// factored with the pivot test the derivative uses, and each link's
/// diagonal block of M⁻¹ kept; or, if a pivot fails, that pivot, for the
/// derivative to report with its time and state.
template <class S, class Model>
void fold_mass_matrix(const S& scene, Model& model) {
  constexpr int N = S::n_v;
  std::array<double, S::n_q> q{};
  neutral_configuration(scene, q.data());
  const auto motions = link_motions<spatial_algebra, double, true>(scene, q.data());
  Eigen::Matrix<double, N, N> M;
  std::array<double, N> scale;
  mass_matrix<spatial_algebra>(scene, motions, M, scale.data());
  ldlt_pivots<N, double> f;
  if (const auto p = ldlt_factor<N>(M, f, scale.data(), mass_factor<S>{}); p.index >= 0) {
    model.mass_pivot = p;
    return;
  }
  model.mass_pivot = {};
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    for (int j = 0; j < LI::nv; ++j) {
      std::array<double, N> e{}, x;
      e[LI::v + j] = 1;
      ldlt_solve<N>(M, f, e.data(), x.data(), mass_factor<S>{});
      for (int i = 0; i < LI::nv; ++i) model.inverse_mass[folded_mass_offset<S, L>() + i * LI::nv + j] = x[LI::v + i];
    }
  });
}

}  // namespace flange::detail
