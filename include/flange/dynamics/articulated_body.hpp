// Forward dynamics by Featherstone's articulated-body algorithm.
//
// It is flange's second algorithm: it shares the joints' motions and the
// scene's constants with Newton–Euler plus the mass matrix, but none of their
// passes, so the two agreeing is a real check. It runs in the same algebras
// (algebra.hpp): 6-D in space, 3-D (ω_K and the plane's two directions) for a
// planar scene, with motions (ω̇, a) and forces (n, f) at each link's origin
// in link coordinates, accelerations "classic" as in kinematics.hpp:
//
//   down:  c = the velocity-product acceleration of the link at v̇ = 0,
//          p_A = (ω × I·ω, ω × (ω × h)) − loads,   I_A = the link's inertia
//   up:    U = I_A·S, D = Sᵀ·U, u = τ − Sᵀ·p_A,
//          parent's I_A += Xᵀ·(I_A − U·D⁻¹·Uᵀ)·X, p_A += Xᵀ·(p_A + I_a·c + U·D⁻¹·u)
//   down:  a' = X·a_P + c, v̇ = D⁻¹·(u − Uᵀ·a'), a = a' + S·v̇
//
// with X the link's motion transform (rotation E, offset p) and a₀ = (0, −g).
// Its matrices are dense in the algebra's dimensions.
#pragma once
#include "flange/scene/named_state.hpp"
#include "flange/detail/inline.hpp"
#include <array>
#include <tuple>

#include "flange/dynamics/forward_dynamics.hpp"

namespace flange {

namespace detail {

/// The dimensions of algebra A as (angular or linear, component) pairs.
template <class A>
constexpr auto algebra_dims() {
  if constexpr (A::planar) {
    constexpr int K = A::normal;
    return std::array<std::pair<bool, int>, 3>{{{true, K}, {false, (K + 1) % 3}, {false, (K + 2) % 3}}};
  } else {
    return std::array<std::pair<bool, int>, 6>{{{true, 0}, {true, 1}, {true, 2}, {false, 0}, {false, 1}, {false, 2}}};
  }
}
template <class A>
inline constexpr int algebra_size = int(algebra_dims<A>().size());

template <class A, class T>
using dvec = Eigen::Matrix<T, algebra_size<A>, 1>;
template <class A, class T>
using dmat = Eigen::Matrix<T, algebra_size<A>, algebra_size<A>>;

/// A typed pair (motion or force) as a dense vector of the algebra, and back.
template <class A, class T, class P0, class P1>
dvec<A, T> to_dense(const P0& ang, const P1& lin) {
  constexpr auto dims = algebra_dims<A>();
  dvec<A, T> r;
  const Vec3<T> a = ang.dense(), l = lin.dense();
  for (int i = 0; i < algebra_size<A>; ++i) r(i) = dims[i].first ? a(dims[i].second) : l(dims[i].second);
  return r;
}
template <class A, class T>
auto from_dense(const dvec<A, T>& x) {
  constexpr auto dims = algebra_dims<A>();
  Vec3<T> ang = Vec3<T>::Zero(), lin = Vec3<T>::Zero();
  for (int i = 0; i < algebra_size<A>; ++i) (dims[i].first ? ang : lin)(dims[i].second) = x(i);
  return motion_pair{to_svec<A::angular_mask>(ang), to_svec<A::linear_mask>(lin)};
}

/// The motion transform X of a link (parent coordinates → child): for a
/// parent motion (α, a), (E·α, E·(a + α × p)); built column by column.
template <class A, class T, class M>
dmat<A, T> motion_transform(const M& m) {
  dmat<A, T> X;
  for (int i = 0; i < algebra_size<A>; ++i) {
    dvec<A, T> e = dvec<A, T>::Zero();
    e(i) = T(1);
    const auto b = from_dense<A, T>(e);
    X.col(i) = to_dense<A, T>(rot(m.E(), b.ang), rot(m.E(), b.lin + cross(b.ang, m.p)));
  }
  return X;
}
/// A rigid inertia (m, h, I) as a dense matrix of the algebra: (α, a) ↦ (I·α + h × a, m·a + α × h).
template <class A, class T, class R>
dmat<A, T> inertia_matrix(const R& c) {
  dmat<A, T> I;
  for (int i = 0; i < algebra_size<A>; ++i) {
    dvec<A, T> e = dvec<A, T>::Zero();
    e(i) = T(1);
    const auto b = from_dense<A, T>(e);
    const auto F = inertia_times(c, motion_pair{b.ang, b.lin});
    I.col(i) = to_dense<A, T>(F.n, F.f);
  }
  return I;
}

template <class A, class T, int NV>
struct aba_link {
  dmat<A, T> X, IA;
  dvec<A, T> c, pA, a;
  Eigen::Matrix<T, algebra_size<A>, NV> S, U;
  Eigen::Matrix<T, NV, NV> Dinv;
  Eigen::Matrix<T, NV, 1> u;
  std::array<T, NV> scale;
};

template <class A, class S, class T, class Seq = std::make_integer_sequence<int, S::tree.n_links - 1>>
struct aba_workspace;
template <class A, class S, class T, int... L>
struct aba_workspace<A, S, T, std::integer_sequence<int, L...>> {
  using type = std::tuple<aba_link<A, T, link_info<S, L + 1>::nv>...>;
};

/// The velocity-kinematics pass: ω of each link, its velocity-product
/// acceleration c and its bias force p_A.
template <class A, class S, class T, class Motions, class WS>
struct aba_velocity_pass {
  const S& scene;
  const Motions& motions;
  const T* v;
  const link_loads<S, T>& n_ext;
  const link_loads<S, T>& f_ext;
  WS& ws;

  template <int L, class K>
  nothing at(const K& k) {
    if constexpr (L != 0) {
      auto& w = std::get<L - 1>(ws);
      w.c = to_dense<A, T>(k.wd, k.a);
      const auto rest = link_kinematics{k.w, zero_vec<T>{}, zero_vec<T>{}};
      const auto pA = own_wrench<A, T, L>(scene, rest, n_ext, f_ext);
      w.pA = to_dense<A, T>(pA.n, pA.f);
    }
    return {};
  }
  template <int L, int C, class K>
  auto down(const K& k) {
    // The child's velocity products: forward_step from the parent's ω alone.
    const auto moving = link_kinematics{k.w, zero_vec<T>{}, zero_vec<T>{}};
    return forward_step<T>(moving, std::get<C - 1>(motions), v + link_info<S, C>::v, no_rates{});
  }
  template <int, int>
  nothing gather(nothing, nothing) {
    return {};
  }
  template <int, class D>
  nothing leave(const D&, nothing) {
    return {};
  }
};

}  // namespace detail

/// v̇ at (t, q, v) by the articulated-body algorithm, in algebra A.
template <class A, class S, class T>
void accelerations_articulated_body_in(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  using namespace detail;
  constexpr int NL = S::tree.n_links;
  const auto xs = state_view<S>(q, v);
  typename aba_workspace<A, S, T>::type ws;
  const auto motions = algebra_motions<A>(scene, q);
  {
    link_loads<S, T> n_ext, f_ext;
    gather_external<A>(scene, t, xs, motions, pose_motions<A>(scene, q, motions), n_ext, f_ext);
    std::array<T, S::n_v> tau;
    joint_forces(scene, t, xs, tau.data());
    for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      auto& w = std::get<L - 1>(ws);
      const auto& m = std::get<L - 1>(motions);
      w.X = motion_transform<A, T>(m);
      [&]<int... K>(std::integer_sequence<int, K...>) FLANGE_INLINE_LAMBDA {
        ((w.S.col(K) = to_dense<A, T>(m.template col<K>().ang, m.template col<K>().lin)), ...);
      }(std::make_integer_sequence<int, LI::nv>{});
      w.IA = inertia_matrix<A, T>(link_inertia<A, T, L>(scene));
    });
    aba_velocity_pass<A, S, T, std::remove_cvref_t<decltype(motions)>, decltype(ws)> vel{scene, motions, v, n_ext, f_ext,
                                                                                          ws};
    walk<S, 0>(vel, link_kinematics{zero_vec<T>{}, zero_vec<T>{}, zero_vec<T>{}});
    for_links_reverse<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      constexpr int nv = LI::nv;
      auto& w = std::get<L - 1>(ws);
      w.U = w.IA * w.S;
      Eigen::Matrix<T, nv, nv> D = w.S.transpose() * w.U;
      // The relative pivot test of ldlt.hpp, against the trace of the
      // articulated inertia's block each column moves in.
      constexpr auto dims = algebra_dims<A>();
      for (int k = 0; k < nv; ++k) {
        T s = T(0);
        bool ang = false, lin = false;
        for (int i = 0; i < algebra_size<A>; ++i)
          if (w.S(i, k) != T(0)) (dims[i].first ? ang : lin) = true;
        for (int i = 0; i < algebra_size<A>; ++i)
          if ((dims[i].first && ang) || (!dims[i].first && lin)) s += w.IA(i, i);
        w.scale[k] = s;
      }
      Eigen::Matrix<T, nv, nv> Dinv;
      for (int k = 0; k < nv; ++k) {
        Eigen::Matrix<T, nv, nv> Dk = D;
        std::array<T, nv> e{}, col{};
        e[k] = T(1);
        if (const auto p = solve_spd<nv>(Dk, e.data(), col.data(), w.scale.data()); p.index >= 0) [[unlikely]]
          throw simulation_error(concat("flange: singular articulated inertia at joint \"", S::table.names[LI::joint],
                                        "\" at t = ", static_cast<double>(t), ", ", describe_state(q, S::n_q, v, S::n_v),
                                        ": pivot ", static_cast<double>(p.d), " against ", static_cast<double>(p.scale)),
                                 static_cast<double>(t));
        for (int i = 0; i < nv; ++i) Dinv(i, k) = col[i];
      }
      w.Dinv = Dinv;
      for (int k = 0; k < nv; ++k) w.u(k) = tau[LI::v + k];
      w.u -= w.S.transpose() * w.pA;
      if constexpr (LI::parent != 0 && nv == algebra_size<A>) {
        // A joint that frees every direction (FreeMotion; a Planar joint in
        // planar algebra) passes its parent no articulated inertia, and of
        // the force only its own generalized force, S⁻ᵀ·τ. The general
        // formula below reaches both only through cancellation (IA − U·D⁻¹·Uᵀ
        // and pA − U·D⁻¹·Sᵀ·pA), whose round-off is that of the heavy child
        // and can swamp a light parent (tests/hard_mass_ratio_test.cpp:
        // masses from 1e-6 to 1e6 made a parent's articulated inertia negative).
        if constexpr (has_generalized_force<typename LI::joint_type>) {
          Eigen::Matrix<T, nv, 1> tj;
          for (int k = 0; k < nv; ++k) tj(k) = tau[LI::v + k];
          const dvec<A, T> pa = w.S.transpose().partialPivLu().solve(tj);
          std::get<LI::parent - 1>(ws).pA += w.X.transpose() * pa;
        }
      } else if constexpr (LI::parent != 0) {
        auto& p = std::get<LI::parent - 1>(ws);
        const dmat<A, T> Ia = w.IA - w.U * w.Dinv * w.U.transpose();
        const dvec<A, T> pa = w.pA + Ia * w.c + w.U * (w.Dinv * w.u);
        p.IA += w.X.transpose() * Ia * w.X;
        p.pA += w.X.transpose() * pa;
      }
    });
    const auto base = base_kinematics<A, T>(scene);
    const dvec<A, T> a0 = to_dense<A, T>(base.wd, base.a);
    for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
      constexpr int L = decltype(l)::value;
      using LI = link_info<S, L>;
      auto& w = std::get<L - 1>(ws);
      const dvec<A, T>* aP = &a0;
      if constexpr (LI::parent != 0) aP = &std::get<LI::parent - 1>(ws).a;
      const dvec<A, T> ap = w.X * *aP + w.c;
      const Eigen::Matrix<T, LI::nv, 1> acc = w.Dinv * (w.u - w.U.transpose() * ap);
      for (int k = 0; k < LI::nv; ++k) vdot[LI::v + k] = acc(k);
      w.a = ap + w.S * acc;
    });
    (void)NL;
  }
}

/// v̇ at (t, q, v) by the articulated-body algorithm, in the algebra the scene calls for.
template <class S, class T>
void accelerations_articulated_body(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  accelerations_articulated_body_in<algebra_t<S>>(scene, t, q, v, vdot);
}

}  // namespace flange
