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

#include <Eigen/Cholesky>

#include "flange/dynamics/model.hpp"
#include "flange/dynamics/tree_walk.hpp"

namespace flange {

namespace detail {

template <class T>
struct ne_link {
  Vec3<T> w = Vec3<T>::Zero(), wd = Vec3<T>::Zero(), a = Vec3<T>::Zero();
  Vec3<T> f = Vec3<T>::Zero(), n = Vec3<T>::Zero();
  Vec3<T> p = Vec3<T>::Zero();  // child origin from parent origin, parent coordinates
};

template <class S, class T, class X>
void newton_euler_bias(const S& scene, const T* qd, const X& xf, const std::array<Vec3<T>, S::tree.n_links>& n_ext,
                       std::array<ne_link<T>, S::tree.n_links>& lk, T* b) {
  constexpr bool gravity = S::has_gravity;
  Vec3<T> minus_g = Vec3<T>::Zero();
  if constexpr (gravity) minus_g = -scene.gravity().template cast<T>();
  const auto& model = scene.model();
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    const T qdl = qd[LI::q];
    auto& c = lk[L];
    if constexpr (LI::has_offset) c.p = model.set_offset[LI::parent_set].template cast<T>() + x.p();
    else c.p = x.p();
    if constexpr (LI::parent == 0) {
      // The world link neither turns nor accelerates (but for −g).
      if constexpr (XF::rotates) {
        c.w = x.axis(qdl);
        if constexpr (gravity) c.a = x.rot(minus_g);
      } else {
        if constexpr (gravity) c.a = minus_g;
      }
    } else {
      const auto& P = lk[LI::parent];
      Vec3<T> ap = P.a;
      if constexpr (LI::has_offset || XF::translates) ap += P.wd.cross(c.p) + P.w.cross(P.w.cross(c.p));
      if constexpr (XF::rotates) {
        c.w = x.rot(P.w) + x.axis(qdl);
        c.wd = x.rot(P.wd) + x.cross_axis(c.w, qdl);
        c.a = x.rot(ap);
      } else {
        c.w = P.w;
        c.wd = P.wd;
        c.a = ap + T(2) * c.w.cross(x.axis(qdl));
      }
    }
    const auto& I = model.link[L];
    const Vec3<T> h = I.h.template cast<T>();
    const Mat3<T> Io = I.I.template cast<T>();
    c.f = T(I.m) * c.a + c.wd.cross(h) + c.w.cross(c.w.cross(h));
    c.n = Io * c.wd + c.w.cross(Io * c.w) + h.cross(c.a) - n_ext[L];
  });
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    auto& c = lk[L];
    b[LI::q] = XF::rotates ? x.axis_dot(c.n) : x.axis_dot(c.f);
    if constexpr (LI::parent != 0) {
      auto& P = lk[LI::parent];
      const Vec3<T> fp = x.rot_t(c.f);
      P.f += fp;
      P.n += x.rot_t(c.n) + c.p.cross(fp);
    }
  });
}

/// Column L of the mass matrix from the composite inertia of link L's subtree.
template <class S, int L, int J, class T, class X, class MM>
void crba_column(const X& xf, const std::array<ne_link<T>, S::tree.n_links>& lk, const Vec3<T>& n, const Vec3<T>& f,
                 MM& M) {
  using LJ = link_info<S, J>;
  constexpr int P = LJ::parent;
  if constexpr (P != 0) {
    const auto& x = std::get<J - 1>(xf);
    const Vec3<T> fp = x.rot_t(f);
    const Vec3<T> np = x.rot_t(n) + lk[J].p.cross(fp);
    using LP = link_info<S, P>;
    using XP = typename LP::template transform<T>;
    const auto& xp = std::get<P - 1>(xf);
    const T v = XP::rotates ? xp.axis_dot(np) : xp.axis_dot(fp);
    M(LP::q, link_info<S, L>::q) = v;
    M(link_info<S, L>::q, LP::q) = v;
    crba_column<S, L, P>(xf, lk, np, fp, M);
  }
}

template <class S, class T, class X, class MM>
void composite_rigid_body(const S& scene, const X& xf, const std::array<ne_link<T>, S::tree.n_links>& lk, MM& M) {
  constexpr int NL = S::tree.n_links;
  std::array<rigid_inertia<T>, NL> ic;
  for (int L = 1; L < NL; ++L) {
    const auto& I = scene.model().link[L];
    ic[L].m = T(I.m);
    ic[L].h = I.h.template cast<T>();
    ic[L].I = I.I.template cast<T>();
  }
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    const auto& c = ic[L];
    Vec3<T> n, f;
    if constexpr (XF::rotates) {
      const Vec3<T> s = x.axis(T(1));
      n = c.I * s;
      f = s.cross(c.h);
      M(LI::q, LI::q) = x.axis_dot(n);
    } else {
      const Vec3<T> s = x.axis(T(1));
      n = c.h.cross(s);
      f = c.m * s;
      M(LI::q, LI::q) = c.m;
    }
    crba_column<S, L, L>(xf, lk, n, f, M);
    if constexpr (LI::parent != 0) {
      rigid_inertia<T> r;
      r.m = c.m;
      if constexpr (XF::rotates) {
        const Mat3<T> E = x.matrix();
        r.h = E.transpose() * c.h;
        r.I = E.transpose() * c.I * E;
      } else {
        r.h = c.h;
        r.I = c.I;
      }
      ic[LI::parent].add_shifted(r, lk[L].p);
    }
  });
}

/// Generalised joint forces from joint inputs (a Prismatic's f).
template <class S, class T>
void joint_inputs(const S& scene, const T& t, const joint_state<T>& x, T* tau) {
  for (int i = 0; i < S::n_q; ++i) tau[i] = T(0);
  for_links<S>([&](auto l) {
    using LI = link_info<S, decltype(l)::value>;
    if constexpr (LI::joint_type::has_input) tau[LI::q] = scene.template component<LI::joint>().generalized_force(t, x);
  });
}

}  // namespace detail

/// q̈ = M⁻¹·(τ − b) at (t, q, q̇). Throws simulation_error if M is singular.
template <class S, class T>
void accelerations_newton_euler(const S& scene, const T& t, const T* q, const T* qd, T* qdd) {
  constexpr int N = S::n_q, NL = S::tree.n_links;
  const auto xf = detail::joint_transforms(scene, q);
  const joint_state<T> x{q, qd, N};
  std::array<Vec3<T>, NL> n_ext;
  n_ext.fill(Vec3<T>::Zero());
  detail::gather_external(scene, t, x, xf, n_ext);
  std::array<detail::ne_link<T>, NL> lk;
  std::array<T, N> b, tau;
  detail::newton_euler_bias(scene, qd, xf, n_ext, lk, b.data());
  detail::joint_inputs(scene, t, x, tau.data());
  Eigen::Matrix<T, N, N> M;
  detail::composite_rigid_body(scene, xf, lk, M);
  using std::isfinite;
  if constexpr (N == 1) {
    if (!(M(0, 0) > T(0)) || !isfinite(static_cast<double>(M(0, 0))))
      throw simulation_error(detail::concat("flange: singular mass matrix (M = ", static_cast<double>(M(0, 0)),
                                            ") at t = ", static_cast<double>(t), ", ", detail::describe_state(q, qd, N),
                                            "; a joint moves nothing with mass or inertia"),
                             static_cast<double>(t));
    qdd[0] = (tau[0] - b[0]) / M(0, 0);
  } else {
    const Eigen::LLT<Eigen::Matrix<T, N, N>> llt(M);
    if (llt.info() != Eigen::Success)
      throw simulation_error(detail::concat("flange: singular mass matrix at t = ", static_cast<double>(t), ", ",
                                            detail::describe_state(q, qd, N),
                                            "; some joint moves nothing with mass or inertia"),
                             static_cast<double>(t));
    Eigen::Matrix<T, N, 1> r;
    for (int i = 0; i < N; ++i) r(i) = tau[i] - b[i];
    const Eigen::Matrix<T, N, 1> a = llt.solve(r);
    for (int i = 0; i < N; ++i) qdd[i] = a(i);
  }
}

/// The mass matrix M(q) (for tests and users who want it).
template <class S, class T>
Eigen::Matrix<T, S::n_q, S::n_q> mass_matrix(const S& scene, const T* q) {
  constexpr int NL = S::tree.n_links;
  const auto xf = detail::joint_transforms(scene, q);
  std::array<T, S::n_q> qd{};
  std::array<Vec3<T>, NL> n_ext;
  n_ext.fill(Vec3<T>::Zero());
  std::array<detail::ne_link<T>, NL> lk;
  std::array<T, S::n_q> b;
  detail::newton_euler_bias(scene, qd.data(), xf, n_ext, lk, b.data());
  Eigen::Matrix<T, S::n_q, S::n_q> M;
  detail::composite_rigid_body(scene, xf, lk, M);
  return M;
}

}  // namespace flange
