// Forward dynamics by Featherstone's articulated-body algorithm.
//
// One of flange's two forward algorithms (algorithm.hpp picks one per scene;
// large trees get this one, whose work grows linearly with the links). It
// shares the joints' motions and the scene's constants with Newton–Euler plus
// the mass matrix, but none of their passes, so the two agreeing is a real
// check (other_algorithm.hpp). It runs in the algebras of algebra.hpp, with
// motions (ω̇, a) and forces (n, f) at each link's origin in link
// coordinates, accelerations "classic" as in kinematics.hpp, and three steps
// per link, as Pinocchio writes them (AbaForwardStep1, AbaBackwardStep,
// AbaForwardStep2):
//
//   start (parents first):  c = the velocity-product acceleration at v̇ = 0,
//                           p_A = (ω × I·ω, ω × (ω × h)) − loads, I_A = I
//   up (children first):    U = I_A·S, D = Sᵀ·U, u = τ − Sᵀ·p_A,
//                           parent's I_A += Xᵀ·(I_A − U·D⁻¹·Uᵀ)·X,
//                           parent's p_A += Xᵀ·(p_A + I_a·c + U·D⁻¹·u)
//   down (parents first):   a' = X·a_P + c, v̇ = D⁻¹·(u − Uᵀ·a'), a = a' + S·v̇
//
// with X the link's motion transform (rotation E, offset p), a₀ = (0, −g) and
// I_A an articulated inertia (articulated_inertia.hpp). Where the tree is
// mostly one chain the step down takes v̇ = b − Gᵀ·a_P, b and G formed in the
// step up (aba_link, the plan's early form).
//
// The steps say what a link computes. How they run (one link or a block of
// links at a time, unrolled into the pass or shared between links of one
// kind, each unit a function of its own in a large scene) is the plan's and
// the executor's (schedule.hpp). The driver, accelerations_articulated_body_in,
// holds one evaluation's records and hands each unit its links (unit_links)
// and what their parent left (parent_of).
#pragma once
#include <array>
#include <cstddef>
#include <new>
#include <tuple>
#include <type_traits>
#include <utility>

#include "flange/detail/inline.hpp"
#include "flange/dynamics/articulated_inertia.hpp"
#include "flange/dynamics/forward_dynamics.hpp"
#include "flange/dynamics/schedule.hpp"
#include "flange/scene/named_state.hpp"

namespace flange {

namespace detail {

/// A link's record: what its steps leave for each other.
template <class A, class T, int NV, bool Early>
struct aba_link {
  // Not zeroed: every entry is written before it is read (the workspace is a
  // tuple, which would otherwise value-initialise it at every evaluation, and
  // the tests' NaN-filled stacks would not see a read before a write).
  aba_link() {}
  svec<T, A::angular_mask> w;  ///< ω
  articulated_inertia<A, T> IA;
  aba_force<A, T> pA;
  aba_motion<A, T> c, a;
  /// What the step down takes from the step up, in one of two forms:
  ///  early:  v̇ = b − Gᵀ·a_P, with b = D⁻¹·(u − Uᵀ·c) and G = Xᵀ·U·D⁻¹ (by
  ///          column, a force in the parent's coordinates), formed in the
  ///          step up, where they wait for nothing;
  ///  late:   v̇ = D⁻¹·(b − Gᵀ·a'), a' = X·a_P + c, with b = u and G = U.
  static constexpr bool early = Early;
  std::array<T, NV> b;
  std::array<aba_force<A, T>, NV> G;
  struct none {};
  [[no_unique_address]] std::conditional_t<early, none, Eigen::Matrix<T, NV, NV>> Dinv;
};

/// What the bodies and loads of a link are: the kinds its steps are written for.
struct link_kind {
  bool h_zero;
  int I_kind;
  bool torque, force;
};
template <class S, int L>
constexpr link_kind kind_of() {
  constexpr auto K = inertia_kinds<S>::value;
  constexpr auto F = load_flags<S>::value;
  return {K.h_zero[L], K.I_kind[L], F.torque[L], F.force[L]};
}

/// D⁻¹ for D = Sᵀ·I_A·S, with the relative pivot test of ldlt.hpp against the
/// trace of the articulated inertia's blocks each column moves in. Returns
/// the first failing pivot (index among the joint's rates).
template <class A, class T, class Mo, std::size_t NV>
FLANGE_INLINE pivot_report<T> aba_invert_d(const std::array<aba_force<A, T>, NV>& U, const articulated_inertia<A, T>& IA,
                                           const Mo& m, Eigen::Matrix<T, int(NV), int(NV)>& Dinv) {
  constexpr int nv = int(NV);
  Eigen::Matrix<T, nv, nv> D;
  std::array<T, nv> scale;
  static_for<nv>([&](auto k) FLANGE_INLINE_LAMBDA {
    constexpr int K = decltype(k)::value;
    const auto s = m.template col<K>();
    const auto g = m.project(U[K].n, U[K].f);
    for (int i = 0; i < nv; ++i) D(i, K) = g[i];
    scale[K] = IA.scale(!is_zero_vec<decltype(s.ang)>, !is_zero_vec<decltype(s.lin)>);
  });
  ldlt_pivots<nv, T> f;
  if (const auto p = ldlt_factor<nv>(D, f, scale.data()); p.index >= 0) [[unlikely]]
    return p;
  for (int k = 0; k < nv; ++k) {
    std::array<T, nv> e{}, col{};
    e[k] = T(1);
    ldlt_solve<nv>(D, f, e.data(), col.data());
    for (int i = 0; i < nv; ++i) Dinv(i, k) = col[i];
  }
  return {};
}

/// The first step, parents first: the link's ω from its parent's wP, its
/// velocity-product acceleration c, its bias force p_A, and its own inertia
/// I (the model's record, of kinds K) as the start of I_A. block<R>: R links
/// in a row, each the parent of the next.
template <class A, class T, link_kind K>
struct aba_start_step {
  template <class W, class Mo, class WP>
  FLANGE_INLINE static void run(W& w, const Mo& m, const WP& wP, const rigid_inertia<double>& I, const T* v,
                                const Vec3<T>& n_ext, const Vec3<T>& f_ext) {
    const auto k = forward_step<T>(link_kinematics{wP, zero_vec<T>{}, zero_vec<T>{}}, m, v, no_rates{});
    w.w = fit<A::angular_mask>(k.w);
    w.c = as_motion<A, T>(k.wd, k.a);
    const auto pA = own_wrench_of<A, T, K.torque, K.force>(link_inertia_of<A, T, K.h_zero, K.I_kind>(I),
                                                           link_kinematics{k.w, zero_vec<T>{}, zero_vec<T>{}},
                                                           n_ext, f_ext);
    w.pA = as_force<A, T>(pA.n, pA.f);
    // Built in place, not assigned: GCC left a record's assignment out of
    // line in a large translation unit, a call per link and spills around it.
    using inertia_type = articulated_inertia<A, T>;
    ::new (static_cast<void*>(&w.IA)) inertia_type(inertia_type::rigid(link_inertia_of<A, T, K.h_zero, K.I_kind>(I)));
  }
  template <int R>
  struct block {
    template <class W, class Mo, class WP>
    FLANGE_INLINE static void run(W* const* wp, const Mo* const* mp, const WP& wP, const rigid_inertia<double>* I,
                                  const T* v, const Vec3<T>* n_ext, const Vec3<T>* f_ext) {
      constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
      aba_start_step::run(*wp[0], *mp[0], wP, I[0], v, n_ext[0], f_ext[0]);
      static_for<R - 1>([&](auto k) FLANGE_INLINE_LAMBDA {
        constexpr int J = decltype(k)::value + 1;
        aba_start_step::run(*wp[J], *mp[J], wp[J - 1]->w, I[J], v + J * nv, n_ext[J], f_ext[J]);
      });
    }
  };
};

/// The step up, children first: U = I_A·S, D⁻¹, u = τ − Sᵀ·p_A, the step
/// down's b and G, and the parent's shares I_A += Xᵀ·I_a·X and
/// p_A += Xᵀ·(p_A + I_a·c + U·D⁻¹·u), I_a = I_A − U·D⁻¹·Uᵀ. Returns D⁻¹'s
/// failing pivot, if any. block<R>: R links in a row, each handing the one
/// before it (its parent) its shares in registers.
template <class A, class T, bool JointForces>
struct aba_up_step {
  /// Given the link's I_A and p_A (its children's shares added), the
  /// parent's shares to *ip and *fp (nullptr: no parent).
  template <class W, class Mo, class IA_, class PA_, class IP, class FP>
  FLANGE_INLINE static pivot_report<T> carry(W& w, const Mo& m, IA_& IA, const PA_& pA, IP* ip, FP* fp, const T* tau) {
    constexpr int nv = std::tuple_size_v<decltype(w.b)>;
    // U, D⁻¹ and u: the step's own in the early form, written where the
    // step down reads them in the late form.
    std::array<aba_force<A, T>, nv> UDinv, U_own;
    Eigen::Matrix<T, nv, nv> Dinv_own;
    std::array<T, nv> u_own;
    auto& U = pick<W::early>(U_own, w.G);
    static_for<nv>([&](auto k) FLANGE_INLINE_LAMBDA {
      U[k] = IA.times(m.template col<decltype(k)::value>().ang, m.template col<decltype(k)::value>().lin);
    });
    auto& Dinv = pick<W::early>(Dinv_own, w.Dinv);
    if (const auto piv = aba_invert_d(U, IA, m, Dinv); piv.index >= 0) [[unlikely]]
      return piv;
    auto& u = pick<W::early>(u_own, w.b);
    const auto sp = m.project(pA.n, pA.f);
    for (int k = 0; k < nv; ++k) {
      if constexpr (JointForces) u[k] = tau[k] - sp[k];
      else u[k] = -sp[k];
    }
    for (int k = 0; k < nv; ++k) {
      auto n = Dinv(0, k) * U[0].n;
      auto f = Dinv(0, k) * U[0].f;
      for (int i = 1; i < nv; ++i) {
        n = n + Dinv(i, k) * U[i].n;
        f = f + Dinv(i, k) * U[i].f;
      }
      UDinv[k] = {n, f};
    }
    if constexpr (W::early) {  // v̇ = D⁻¹·(u − Uᵀ·(X·a_P + c)) as b − Gᵀ·a_P
      std::array<T, nv> r;
      for (int k = 0; k < nv; ++k)
        r[k] = u[k] - (value_of<T>(dot(U[k].n, w.c.ang)) + value_of<T>(dot(U[k].f, w.c.lin)));
      for (int i = 0; i < nv; ++i) {
        w.b[i] = Dinv(i, 0) * r[0];
        for (int k = 1; k < nv; ++k) w.b[i] += Dinv(i, k) * r[k];
        const auto g = carry_up(m, force_pair{UDinv[i].n, UDinv[i].f});
        w.G[i] = as_force<A, T>(g.n, g.f);
      }
    }
    if constexpr (!std::is_same_v<IP, std::nullptr_t>) {
      constexpr auto Z = known_zero_dims<Mo, nv>();
      IA.template subtract<Z.first, Z.second>(UDinv, U);
      const auto Iac = IA.template times<Z.first, Z.second>(w.c.ang, w.c.lin);
      auto pn = pA.n + Iac.n;
      auto pf = pA.f + Iac.f;
      for (int k = 0; k < nv; ++k) {
        pn = pn + u[k] * UDinv[k].n;
        pf = pf + u[k] * UDinv[k].f;
      }
      ip->template add_from_child<Z.first, Z.second>(IA, m);
      const auto up = carry_up(m, force_pair{pn, pf});
      *fp = as_force<A, T>(fp->n + up.n, fp->f + up.f);
    }
    return {};
  }
  /// carry with the parent's shares going to the record of parent p (nullptr: none).
  template <class W, class Mo, class IA_, class PA_, class P>
  FLANGE_INLINE static pivot_report<T> to(W& w, const Mo& m, IA_& IA, const PA_& pA, P* p, const T* tau) {
    if constexpr (std::is_same_v<P, std::nullptr_t>) return carry(w, m, IA, pA, p, p, tau);
    else return carry(w, m, IA, pA, &p->IA, &p->pA, tau);
  }
  /// One link. A planar record (9 and 3 numbers), just written entry by
  /// entry by its children's steps, is read alone (math/read_alone.hpp) and
  /// worked on in registers; a spatial one (27 and 6) in place: copied out,
  /// it spilled.
  template <class W, class Mo, class P>
  FLANGE_INLINE static pivot_report<T> run(W& w, const Mo& m, P* p, const T* tau) {
    if constexpr (A::planar) {
      auto IA = read_alone(w.IA);
      const auto pA = read_alone(w.pA);
      return to(w, m, IA, pA, p, tau);
    } else {
      return to(w, m, w.IA, w.pA, p, tau);
    }
  }
  template <int R>
  struct block {  // the failing pivot's index counts the block's rates from the first link's
    template <class W, class Mo, class P>
    FLANGE_INLINE static pivot_report<T> run(W* const* wp, const Mo* const* mp, P* p, const T* tau) {
      constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
      auto IA = read_alone(wp[R - 1]->IA);
      auto pA = read_alone(wp[R - 1]->pA);
      pivot_report<T> piv{};
      const bool ok = [&]<int... J>(std::integer_sequence<int, J...>) FLANGE_INLINE_LAMBDA {
        return ([&]() FLANGE_INLINE_LAMBDA {
          constexpr int k = R - 1 - J;
          if constexpr (k > 0) {
            auto IAn = read_alone(wp[k - 1]->IA);
            auto pAn = read_alone(wp[k - 1]->pA);
            piv = carry(*wp[k], *mp[k], IA, pA, &IAn, &pAn, tau + k * nv);
            IA = IAn;
            pA = pAn;
          } else {
            piv = to(*wp[0], *mp[0], IA, pA, p, tau);
          }
          if (piv.index >= 0) [[unlikely]] {
            piv.index += k * nv;
            return false;
          }
          return true;
        }() && ...);
      }(std::make_integer_sequence<int, R>{});
      if (!ok) [[unlikely]]
        return piv;
      return {};
    }
  };

 private:
  template <bool Early, class Own, class Record>
  FLANGE_INLINE static auto& pick(Own& own, Record& record) {
    if constexpr (Early) return own;
    else return record;
  }
};

/// The step down, parents first, from the parent's acceleration aP:
/// v̇ = D⁻¹·(u − Uᵀ·a') into vdot, a' = X·a_P + c, and, for a link with
/// children, a = a' + S·v̇ returned (kept in its record if StoreA).
/// block<R>: R links in a row, each handing the next its a in registers.
template <class A, class T, bool HasChildren, bool StoreA = HasChildren>
struct aba_down_step {
  template <class W, class Mo, class AP>
  FLANGE_INLINE static auto run(W& w, const Mo& m, const AP& aP, T* vdot) {
    constexpr int nv = std::tuple_size_v<decltype(w.b)>;
    const auto minus_g = [&](const auto& x, std::array<T, nv>& r) FLANGE_INLINE_LAMBDA {  // b − Gᵀ·x
      for (int i = 0; i < nv; ++i)
        r[i] = w.b[i] - (value_of<T>(dot(w.G[i].n, x.ang)) + value_of<T>(dot(w.G[i].f, x.lin)));
    };
    // a' = X·a_P + c, formed once, before v̇ is written (vdot may alias what it reads).
    const auto ap = [&]() FLANGE_INLINE_LAMBDA {
      if constexpr (!W::early || HasChildren)
        return as_motion<A, T>(rot(m.E(), aP.ang) + w.c.ang, rot(m.E(), aP.lin + cross(aP.ang, m.p)) + w.c.lin);
      else return 0;
    }();
    std::array<T, nv> acc;
    if constexpr (W::early) {
      minus_g(aP, acc);
    } else {
      std::array<T, nv> r;
      minus_g(ap, r);
      for (int i = 0; i < nv; ++i) {
        acc[i] = w.Dinv(i, 0) * r[0];
        for (int k = 1; k < nv; ++k) acc[i] += w.Dinv(i, k) * r[k];
      }
    }
    for (int i = 0; i < nv; ++i) vdot[i] = acc[i];
    if constexpr (HasChildren) {
      auto an = ap.ang;
      auto al = ap.lin;
      static_for<nv>([&](auto k) FLANGE_INLINE_LAMBDA {
        an = fit<A::angular_mask>(an + acc[k] * m.template col<decltype(k)::value>().ang);
        al = fit<A::linear_mask>(al + acc[k] * m.template col<decltype(k)::value>().lin);
      });
      const aba_motion<A, T> a{an, al};
      if constexpr (StoreA) w.a = a;
      return a;
    } else {
      return 0;
    }
  }
  template <int R>
  struct block {
    template <class W, class Mo, class AP>
    FLANGE_INLINE static void run(W* const* wp, const Mo* const* mp, const AP& aP, T* vdot) {
      constexpr int nv = std::tuple_size_v<decltype(wp[0]->b)>;
      using inner = aba_down_step<A, T, true, false>;
      auto a = inner::run(*wp[0], *mp[0], aP, vdot);
      static_for<R - 2>([&](auto k) FLANGE_INLINE_LAMBDA {
        constexpr int J = decltype(k)::value + 1;
        a = inner::run(*wp[J], *mp[J], a, vdot + J * nv);
      });
      aba_down_step::run(*wp[R - 1], *mp[R - 1], a, vdot + (R - 1) * nv);
    }
  };
};

/// The links' records, link L at L − 1.
template <class A, class S, class T, class Seq = std::make_integer_sequence<int, S::tree.n_links - 1>>
struct aba_records;
template <class A, class S, class T, int... L>
struct aba_records<A, S, T, std::integer_sequence<int, L...>> {
  using type = std::tuple<aba_link<A, T, link_info<S, L + 1>::nv, aba_early<A, S>>...>;
};

/// What the plan (schedule.hpp) asks of the articulated body for scene S:
/// its links' records and motions, which links are of one kind (a block's
/// links share record and motion types, kinds and loads, follow each other
/// as only children with their rates in a row, and none frees every
/// direction), and what its steps cost unrolled (costs.hpp).
template <class A, class S, class T>
struct aba_kinds {
  static constexpr int NL = S::tree.n_links;
  using records = typename aba_records<A, S, T>::type;
  using motions = std::remove_cvref_t<decltype(algebra_motions<A>(std::declval<const S&>(), std::declval<const T*>()))>;
  /// Element I of tuple X, found as std::get finds it (std::tuple_element
  /// instantiates a class per few elements for every lookup).
  template <class X, int I>
  using element = std::remove_cvref_t<decltype(std::get<I>(std::declval<X&>()))>;
  /// A joint that frees every direction (FreeMotion; a Planar joint in a
  /// plane) passes its parent no articulated inertia, and of the force only
  /// its own generalized force, S⁻ᵀ·τ: the general formula reaches both only
  /// through cancellation, whose round-off is the heavy child's and can swamp
  /// a light parent (tests/hard_mass_ratio_test.cpp).
  template <int L>
  static constexpr bool frees_all = link_info<S, L>::parent != 0 && link_info<S, L>::nv == algebra_size<A>;
  template <int L>
  static constexpr bool joins_previous() {
    if constexpr (L < 2) {
      return false;
    } else {
      using LI = link_info<S, L>;
      using LP = link_info<S, L - 1>;
      constexpr link_kind a = kind_of<S, L>(), b = kind_of<S, L - 1>();
      return LI::parent == L - 1 && children<S, L - 1>().size() == 1 && LI::v == LP::v + LP::nv && !frees_all<L> &&
             !frees_all<L - 1> && std::is_same_v<element<records, L - 1>, element<records, L - 2>> &&
             std::is_same_v<element<motions, L - 1>, element<motions, L - 2>> && a.h_zero == b.h_zero &&
             a.I_kind == b.I_kind && a.torque == b.torque && a.force == b.force;
    }
  }
  template <int MaxLen>
  static constexpr std::array<bool, NL> joins() {
    if constexpr (MaxLen == 1) return {};  // no blocks: nothing to look at
    else return []<int... L>(std::integer_sequence<int, L...>) {
      return std::array<bool, NL>{joins_previous<L>()...};
    }(std::make_integer_sequence<int, NL>{});
  }
  static constexpr int instructions() {
    constexpr auto& k = aba_unrolled_link;
    return []<int... L>(std::integer_sequence<int, L...>) {
      return (0 + ... + (A::planar ? k.planar : general_rotation<S, L + 1>() ? k.general : k.typed));
    }(std::make_integer_sequence<int, NL - 1>{});
  }
};

/// What link L takes from its parent's record in ws: its ω (the World's is
/// zero), its acceleration (the World's: base's, −g), and the record its
/// step up adds its shares to (none for a root link, or one that frees every
/// direction).
template <class K, class S, class T, int L>
struct parent_of {
  static constexpr int p = link_info<S, L>::parent;
  FLANGE_INLINE static auto omega(const typename K::records& ws) {
    if constexpr (p != 0) return std::get<p - 1>(ws).w;
    else return zero_vec<T>{};
  }
  template <class B>
  FLANGE_INLINE static auto acceleration(const typename K::records& ws, const B& base) {
    if constexpr (p != 0) return std::get<p - 1>(ws).a;
    else return motion_pair{base.wd, base.a};
  }
  FLANGE_INLINE static auto record(typename K::records& ws) {
    if constexpr (p != 0 && !K::template frees_all<L>) return &std::get<p - 1>(ws);
    else return static_cast<std::nullptr_t*>(nullptr);
  }
};
/// A joint that frees every direction passes its parent p S⁻ᵀ·τ (aba_kinds),
/// carried through its motion m.
template <class A, class T, int NV, class Mo, class W>
FLANGE_INLINE void joint_force_up(const Mo& m, const T* tau, W& p) {
  Eigen::Matrix<T, NV, NV> St;
  static_for<NV>([&](auto k) FLANGE_INLINE_LAMBDA {
    constexpr int J = decltype(k)::value;
    St.row(J) = to_dense<A, T>(m.template col<J>().ang, m.template col<J>().lin).transpose();
  });
  Eigen::Matrix<T, NV, 1> tj;
  for (int k = 0; k < NV; ++k) tj(k) = tau[k];
  const auto pa = from_dense<A, T>(dvec<A, T>(St.partialPivLu().solve(tj)));
  const auto up = carry_up(m, force_pair{pa.ang, pa.lin});
  p.pA = as_force<A, T>(p.pA.n + up.n, p.pA.f + up.f);
}

}  // namespace detail

/// v̇ at (t, q, v) by the articulated-body algorithm, in algebra A: the three
/// steps over the plan's units.
template <class A, aba_steps Steps = aba_steps::automatic, class S, class T>
void accelerations_articulated_body_in(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  using namespace detail;
  using K = aba_kinds<A, S, T>;
  using P = aba_plan<A, S, Steps, K>;
  const auto xs = state_view(scene, q, v);
  typename K::records ws;
  const auto motions = algebra_motions<A>(scene, q);
  link_loads<S, T> n_ext, f_ext;
  gather_external<A>(scene, t, xs, motions, pose_motions<A>(scene, q, motions), n_ext, f_ext);
  std::array<T, S::n_v> tau;
  if constexpr (has_joint_forces<S>()) joint_forces(scene, t, xs, tau.data());
  const auto parent_omega_ = [&](auto l) FLANGE_INLINE_LAMBDA { return parent_of<K, S, T, decltype(l)::value>::omega(ws); };
  const auto start_unit = [&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int U = decltype(u)::value, L0 = P::units.first[U], R = P::units.len[U];
    using links = unit_links<K, L0, R>;
    const auto wP = parent_omega_(std::integral_constant<int, L0>{});
    const links l(ws, motions);
    run_step<(P::shared_start || R > 1), unit_step<aba_start_step<A, T, kind_of<S, L0>()>, R>>(
        l.records(), l.motions(), wP, links::first(scene.model().link[L0]), v + link_info<S, L0>::v,
        links::first(n_ext[L0]), links::first(f_ext[L0]));
  };
  for_units<P::split, P::units.n>([&](auto u) FLANGE_INLINE_LAMBDA { start_unit(u); });
  const auto report = [&](auto l, const pivot_report<T>& piv) FLANGE_INLINE_LAMBDA {  // a singular mass matrix
    if (piv.index >= 0) [[unlikely]]
      singular_mass_matrix<S>(pivot_report<T>{link_info<S, l>::v + piv.index, piv.d, piv.scale}, t, q, v);
  };
  const auto parent_record_ = [&](auto l) FLANGE_INLINE_LAMBDA { return parent_of<K, S, T, decltype(l)::value>::record(ws); };
  const auto up_unit = [&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int U = decltype(u)::value, L0 = P::units.first[U], R = P::units.len[U];
    using LI = link_info<S, L0>;
    const unit_links<K, L0, R> l(ws, motions);
    auto* parent = parent_record_(std::integral_constant<int, L0>{});
    report(std::integral_constant<int, L0>{}, run_step<P::shared, unit_step<aba_up_step<A, T, has_joint_forces<S>()>, R>>(
                                                  l.records(), l.motions(), parent, tau.data() + LI::v));
    if constexpr (R == 1 && K::template frees_all<L0> && has_generalized_force<typename LI::joint_type>)
      joint_force_up<A, T, LI::nv>(l.motions(), tau.data() + LI::v, std::get<LI::parent - 1>(ws));
  };
  for_units<P::split, P::units.n, true>([&](auto u) FLANGE_INLINE_LAMBDA { up_unit(u); });
  const auto base = base_kinematics<A, T>(scene);
  const auto parent_acceleration_ = [&](auto l) FLANGE_INLINE_LAMBDA { return parent_of<K, S, T, decltype(l)::value>::acceleration(ws, base); };
  const auto down_unit = [&](auto u) FLANGE_INLINE_LAMBDA {
    constexpr int U = decltype(u)::value, L0 = P::units.first[U], R = P::units.len[U];
    using step = unit_step<aba_down_step<A, T, (children<S, L0 + R - 1>().size() > 0)>, R>;
    const auto aP = parent_acceleration_(std::integral_constant<int, L0>{});
    const unit_links<K, L0, R> l(ws, motions);
    run_step<P::shared, step>(l.records(), l.motions(), aP, vdot + link_info<S, L0>::v);
  };
  for_units<P::split, P::units.n>([&](auto u) FLANGE_INLINE_LAMBDA { down_unit(u); });
}

/// v̇ at (t, q, v) by the articulated-body algorithm, in the algebra the scene calls for.
template <aba_steps Steps = aba_steps::automatic, class S, class T>
void accelerations_articulated_body(const S& scene, const T& t, const T* q, const T* v, T* vdot) {
  accelerations_articulated_body_in<algebra_t<S>, Steps>(scene, t, q, v, vdot);
}

}  // namespace flange
