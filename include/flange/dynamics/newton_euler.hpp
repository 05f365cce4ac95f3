// Forward dynamics by Newton–Euler plus the mass matrix (the default).
//
//   M(q)·q̈ = τ(t, q, q̇) − b(q, q̇)
//
// b is the recursive Newton–Euler inverse dynamics at q̈ = 0 (Coriolis,
// centrifugal, gravity, force elements), written with classical 3-vectors in
// link coordinates: per link ω, ω̇ and the origin's acceleration a (gravity
// enters as a base acceleration −g). M is the composite-rigid-body algorithm.
// Both loops run over the scene's links at compile time, so each link is a
// straight-line block with its joint's axis folded in.
#pragma once
#include <array>
#include <limits>
#include <string>


#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/model.hpp"
#include "flange/dynamics/tree_walk.hpp"
#include "flange/math/axial.hpp"

namespace flange {

namespace detail {

/// The model's double-precision constants seen as T: a reference for double,
/// a converted copy otherwise.
template <class T, class M>
decltype(auto) as_scalar(const M& m) {
  if constexpr (std::is_same_v<typename M::Scalar, T>) return (m);
  else return m.template cast<T>().eval();
}

template <class T, int Axis>
using vector_kind = std::conditional_t<(Axis < 0), Vec3<T>, axial<T, (Axis < 0 ? 0 : Axis)>>;

/// Per-link workspace of link L. Left uninitialised on purpose: each field is
/// written exactly when link_flags say it is used, and never read otherwise.
/// ω and ω̇ are axial where the flags know their direction.
template <class S, class T, int L>
struct ne_link {
  vector_kind<T, link_flags<S>::value.w_axis[L]> w;    // ω, link coordinates
  vector_kind<T, link_flags<S>::value.wd_axis[L]> wd;  // ω̇
  Vec3<T> a;     // the origin's acceleration (with −g), link coordinates
  Vec3<T> f, n;  // link force and torque about the origin
  Vec3<T> p;     // child origin from parent origin, parent coordinates
};

template <class S, class T, class Seq = std::make_integer_sequence<int, S::tree.n_links>>
struct ne_workspace;
template <class S, class T, int... L>
struct ne_workspace<S, T, std::integer_sequence<int, L...>> {
  using type = std::tuple<ne_link<S, T, L>...>;
};
template <class S, class T>
using ne_workspace_t = typename ne_workspace<S, T>::type;

template <class S, class T, class X>
void newton_euler_bias(const S& scene, const T* qd, const X& xf, const std::array<Vec3<T>, S::tree.n_links>& n_ext,
                       const std::array<Vec3<T>, S::tree.n_links>& f_ext, ne_workspace_t<S, T>& lk, T* b) {
  constexpr bool gravity = S::has_gravity;
  constexpr auto F = link_flags<S>::value;
  Vec3<T> minus_g = Vec3<T>::Zero();
  if constexpr (gravity) minus_g = -scene.gravity().template cast<T>();
  const auto& model = scene.model();
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    constexpr int P = LI::parent;
    const auto& x = std::get<L - 1>(xf);
    const T qdl = qd[LI::q];
    auto& c = std::get<L>(lk);
    const auto& pl = std::get<P>(lk);
    if constexpr (LI::has_offset) c.p = model.set_offset[LI::parent_set].template cast<T>() + x.p();
    else c.p = x.p();
    // The parent origin's acceleration carried to this link's origin.
    Vec3<T> ap;
    if constexpr (P == 0) ap = minus_g;
    else ap = pl.a;
    if constexpr (!F.p_zero[L]) {
      if constexpr (!F.wd_zero[P]) ap += cross(pl.wd, c.p);
      if constexpr (!F.w_zero[P]) ap += cross(pl.w, cross(pl.w, c.p));
    }
    if constexpr (XF::rotates) {
      if constexpr (F.w_axis[L] >= 0) {
        // ω along the joint axis: ω = ω_P + σ·q̇ along e_i.
        c.w.x = x.axis_dot(Vec3<T>::Unit(F.w_axis[L])) * qdl;
        if constexpr (!F.w_zero[P]) c.w.x += pl.w.x;
      } else if constexpr (F.w_zero[P]) {
        c.w = x.axis(qdl);
      } else {
        c.w = x.rot(dense(pl.w)) + x.axis(qdl);
      }
      if constexpr (!F.wd_zero[L]) {
        if constexpr (F.wd_axis[L] >= 0) {
          c.wd.x = pl.wd.x;
        } else {
          Vec3<T> v = Vec3<T>::Zero();
          if constexpr (F.w_axis[L] < 0) v = x.cross_axis(c.w, qdl);
          if constexpr (!F.wd_zero[P]) v += x.rot(dense(pl.wd));
          c.wd = v;
        }
      }
      c.a = x.rot(ap);
    } else {
      if constexpr (!F.w_zero[L]) c.w = pl.w;
      if constexpr (!F.wd_zero[L]) c.wd = pl.wd;
      c.a = ap;
      if constexpr (!F.w_zero[L]) c.a += T(2) * cross(c.w, x.axis(qdl));
    }
    const auto& I = model.link[L];
    decltype(auto) h = as_scalar<T>(I.h);
    // Link force f (needed by a prismatic joint and by the parent) and torque n
    // about the origin: f = m·a + ω̇ × h + ω × (ω × h), n = I·ω̇ + ω × I·ω + h × a.
    // Terms the flags rule out (h = 0 or I = 0 for mass at the link origin,
    // ω or ω̇ ≡ 0) are never formed.
    if constexpr (F.need_f[L]) {
      c.f = T(I.m) * c.a;
      if constexpr (!F.wd_zero[L] && !F.h_zero[L]) c.f += cross(c.wd, h);
      if constexpr (!F.w_zero[L] && !F.h_zero[L]) c.f += cross(c.w, cross(c.w, h));
      if constexpr (F.has_ext_f[L]) c.f -= f_ext[L];
    }
    constexpr bool n_h = !F.h_zero[L], n_wd = !F.wd_zero[L] && F.I_kind[L] > 0, n_w = !F.w_zero[L] && F.I_kind[L] > 0;
    if constexpr (n_h) c.n = h.cross(c.a);
    if constexpr (n_wd || n_w) {
      decltype(auto) Io = as_scalar<T>(I.I);
      if constexpr (n_wd) accumulate<n_h>(c.n, inertia_times<F.I_kind[L], T>(Io, c.wd));
      if constexpr (n_w) accumulate<n_h || n_wd>(c.n, Vec3<T>(cross(c.w, inertia_times<F.I_kind[L], T>(Io, c.w))));
    }
    if constexpr (!(n_h || n_wd || n_w)) c.n.setZero();
    if constexpr (F.has_ext[L]) c.n -= n_ext[L];
  });
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    auto& c = std::get<L>(lk);
    if constexpr (XF::rotates) b[LI::q] = x.axis_dot(c.n);
    else b[LI::q] = x.axis_dot(c.f);
    if constexpr (LI::parent != 0) {
      auto& P = std::get<LI::parent>(lk);
      const Vec3<T> fp = x.rot_t(c.f);
      if constexpr (F.need_f[LI::parent]) P.f += fp;
      P.n += x.rot_t(c.n);
      if constexpr (!F.p_zero[L]) P.n += c.p.cross(fp);
    }
  });
}

/// Column L of the mass matrix: the composite force F = Ic·S of link L's
/// subtree, carried up through the ancestors J and projected on their axes.
template <class S, int L, int J, class T, class X, class MM>
void crba_column(const X& xf, const ne_workspace_t<S, T>& lk, const Vec3<T>& n, const Vec3<T>& f, MM& M) {
  using LJ = link_info<S, J>;
  constexpr int P = LJ::parent;
  if constexpr (P != 0) {
    const auto& x = std::get<J - 1>(xf);
    const Vec3<T> fp = x.rot_t(f);
    Vec3<T> np = x.rot_t(n);
    if constexpr (!link_flags<S>::value.p_zero[J]) np += std::get<J>(lk).p.cross(fp);
    using LP = link_info<S, P>;
    using XP = typename LP::template transform<T>;
    const auto& xp = std::get<P - 1>(xf);
    T v;
    if constexpr (XP::rotates) v = xp.axis_dot(np);
    else v = xp.axis_dot(fp);
    M(LP::q, link_info<S, L>::q) = v;
    M(link_info<S, L>::q, LP::q) = v;
    crba_column<S, L, P>(xf, lk, np, fp, M);
  }
}

/// E'·I·E for a symmetric I, with E applied column by column (2-D rotations
/// for a compile-time axis).
template <class T, class XF>
Mat3<T> rotate_back(const XF& x, const Mat3<T>& I) {
  Mat3<T> A;
  for (int k = 0; k < 3; ++k) A.col(k) = x.rot_t(I.col(k));  // A = E'·I
  Mat3<T> B;
  for (int k = 0; k < 3; ++k) B.col(k) = x.rot_t(A.row(k).transpose());  // B = E'·A' = (A·E)'
  return B.transpose();
}

/// The mass matrix M into M, and into scale[q] each joint's inertia before its
/// projection on the axis (trace of the composite rotational inertia for a
/// turning joint, the composite mass for a sliding one): what its diagonal
/// would be without cancellation, the yardstick of the relative pivot test.
template <class S, class T, class X, class MM>
void composite_rigid_body(const S& scene, const X& xf, const ne_workspace_t<S, T>& lk, MM& M, T* scale) {
  constexpr int NL = S::tree.n_links;
  constexpr auto F = link_flags<S>::value;
  // Composite inertias are accumulated only for links with children; a leaf's
  // is its own, read from the model without a copy (when T is double).
  constexpr auto has_children = [] {
    std::array<bool, NL> c{};
    for (int L = 1; L < NL; ++L) c[S::tree.link_parent[L]] = true;
    return c;
  }();
  zero_branch_pairs<S>(M);
  std::array<rigid_inertia<T>, NL> ic;
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    if constexpr (has_children[L] || !std::is_same_v<T, double>) {
      const auto& I = scene.model().link[L];
      ic[L].m = T(I.m);
      ic[L].h = I.h.template cast<T>();
      if constexpr (F.need_I[L]) ic[L].I = I.I.template cast<T>();
    }
  });
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    const auto& c = [&]() -> const auto& {
      if constexpr (has_children[L] || !std::is_same_v<T, double>) return ic[L];
      else return scene.model().link[L];
    }();
    const auto s = x.unit();
    Vec3<T> n, f;
    if constexpr (XF::rotates) {
      n = mul<T>(c.I, s);  // F = Ic·S with S = (σn, 0): (I·σn, σn × h)
      f = cross(s, Vec3<T>(c.h));
      M(LI::q, LI::q) = x.axis_dot(n);
      scale[LI::q] = T(c.I.trace());
    } else {
      n = cross(Vec3<T>(c.h), s);  // S = (0, σn): (h × σn, m·σn)
      f = T(c.m) * dense(s);
      M(LI::q, LI::q) = T(c.m);
      scale[LI::q] = T(c.m);
    }
    crba_column<S, L, L>(xf, lk, n, f, M);
    if constexpr (LI::parent != 0) {
      rigid_inertia<T> r;
      r.m = T(c.m);
      r.h = x.rot_t(Vec3<T>(c.h));
      auto& pc = ic[LI::parent];
      if constexpr (F.p_zero[L]) {
        pc.m += r.m;
        pc.h += r.h;
      } else {
        pc.add_shifted_mass(r, std::get<L>(lk).p);
      }
      if constexpr (F.need_I[LI::parent]) {
        if constexpr (XF::rotates) r.I = rotate_back<T>(x, Mat3<T>(c.I));
        else r.I = c.I;
        if constexpr (F.p_zero[L]) pc.I += r.I;
        else pc.add_shifted_rotational(r, std::get<L>(lk).p);
      }
    }
  });
}

/// Generalised joint forces from joint inputs (a Prismatic's f).
template <class S, class T>
void joint_inputs(const S& scene, const T& t, const joint_state<T>& x, T* tau) {
  for (int i = 0; i < S::n_q; ++i) tau[i] = T(0);
  for_links<S>([&](auto l) {
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (LI::joint_type::has_input)
      tau[LI::q] = scene.template component<LI::joint>().generalized_force(t, x, LI::q);
  });
}

}  // namespace detail

namespace detail {
/// The name of the joint whose coordinate is q[i].
template <class S>
constexpr std::string_view joint_name(int i) {
  for (int c = 0; c < S::n_components; ++c)
    if (S::tree.q_index[c] == i) return S::table.names[c];
  return "?";
}
template <class S, class T>
[[noreturn, gnu::cold, gnu::noinline]] void singular_mass_matrix(const pivot_report<T>& p, const T& t, const T* q,
                                                                const T* qd, int n) {
  const double d = static_cast<double>(p.d), scale = static_cast<double>(p.scale);
  const std::string why =
      scale > 0 ? concat("its pivot ", d, " is ", d / scale, " of the inertia it moves (", scale,
                         "), at or below the relative tolerance ", pivot_tolerance<S::n_q, T>(),
                         ": its axis passes through all the mass it moves, or its motion repeats other joints'")
                : std::string("it moves nothing with mass or inertia");
  throw simulation_error(concat("flange: singular mass matrix at t = ", static_cast<double>(t), ", ",
                                describe_state(q, qd, n), ": joint \"", joint_name<S>(p.index), "\" (q[", p.index,
                                "]): ", why),
                         static_cast<double>(t));
}
}  // namespace detail

/// q̈ = M⁻¹·(τ − b) at (t, q, q̇). Throws simulation_error if M is singular.
template <class S, class T>
void accelerations_newton_euler(const S& scene, const T& t, const T* q, const T* qd, T* qdd) {
  constexpr int N = S::n_q, NL = S::tree.n_links;
  const auto xf = detail::joint_transforms(scene, q);
  const joint_state<T> x{q, qd, N};
  std::array<Vec3<T>, NL> n_ext, f_ext;
  detail::gather_external(scene, t, x, xf, n_ext, f_ext);
  detail::ne_workspace_t<S, T> lk;
  std::array<T, N> b, tau;
  detail::newton_euler_bias(scene, qd, xf, n_ext, f_ext, lk, b.data());
  detail::joint_inputs(scene, t, x, tau.data());
  Eigen::Matrix<T, N, N> M;
  std::array<T, N> scale;
  detail::composite_rigid_body<S, T>(scene, xf, lk, M, scale.data());
  std::array<T, N> r;
  for (int i = 0; i < N; ++i) r[i] = tau[i] - b[i];
  if (const auto pivot = detail::solve_spd<N>(M, r.data(), qdd, scale.data()); pivot.index >= 0) [[unlikely]]
    detail::singular_mass_matrix<S>(pivot, t, q, qd, N);
}

/// The mass matrix M(q) (for tests and users who want it).
template <class S, class T>
Eigen::Matrix<T, S::n_q, S::n_q> mass_matrix(const S& scene, const T* q) {
  constexpr int NL = S::tree.n_links;
  const auto xf = detail::joint_transforms(scene, q);
  std::array<T, S::n_q> qd{};
  std::array<Vec3<T>, NL> n_ext, f_ext;
  n_ext.fill(Vec3<T>::Zero());
  f_ext.fill(Vec3<T>::Zero());
  detail::ne_workspace_t<S, T> lk;
  std::array<T, S::n_q> b;
  detail::newton_euler_bias(scene, qd.data(), xf, n_ext, f_ext, lk, b.data());
  Eigen::Matrix<T, S::n_q, S::n_q> M;
  std::array<T, S::n_q> scale;
  detail::composite_rigid_body<S, T>(scene, xf, lk, M, scale.data());
  return M;
}

}  // namespace flange
