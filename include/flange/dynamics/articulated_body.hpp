// Forward dynamics by Featherstone's articulated-body algorithm, in 6-D
// spatial (Plücker) form: motion vectors [ω; v], force vectors [n; f], link
// coordinates at the link origin.
//
// It is flange's second algorithm. It shares nothing with newton_euler.hpp but
// the joint transforms and the precomputed link inertias, so the two agreeing
// is a real check. It is also O(n) where the default is O(n²)–O(n³); the
// benchmarks say which is faster for which scene.
#pragma once
#include <array>

#include "flange/dynamics/model.hpp"
#include "flange/dynamics/ldlt.hpp"
#include "flange/dynamics/tree_walk.hpp"

namespace flange {

namespace detail {
template <class T> using Vec6 = Eigen::Matrix<T, 6, 1>;
template <class T> using Mat6 = Eigen::Matrix<T, 6, 6>;

/// Plücker motion transform parent → child: [E 0; −E·p̃ E].
template <class T>
Mat6<T> motion_transform(const Mat3<T>& E, const Vec3<T>& p) {
  Mat6<T> X = Mat6<T>::Zero();
  X.template topLeftCorner<3, 3>() = E;
  X.template bottomRightCorner<3, 3>() = E;
  X.template bottomLeftCorner<3, 3>() = -E * tilde<T>(p);
  return X;
}
template <class T>
Mat6<T> crm(const Vec6<T>& v) {
  Mat6<T> m = Mat6<T>::Zero();
  const Mat3<T> w = tilde<T>(v.template head<3>());
  m.template topLeftCorner<3, 3>() = w;
  m.template bottomRightCorner<3, 3>() = w;
  m.template bottomLeftCorner<3, 3>() = tilde<T>(v.template tail<3>());
  return m;
}
template <class T>
Mat6<T> spatial_inertia(const rigid_inertia<double>& I) {
  Mat6<T> m;
  const Mat3<T> H = tilde<T>(I.h.template cast<T>());
  m.template topLeftCorner<3, 3>() = I.I.template cast<T>();
  m.template topRightCorner<3, 3>() = H;
  m.template bottomLeftCorner<3, 3>() = H.transpose();
  m.template bottomRightCorner<3, 3>() = T(I.m) * Mat3<T>::Identity();
  return m;
}
}  // namespace detail

/// q̈ at (t, q, q̇) by the articulated-body algorithm.
template <class S, class T>
void accelerations_articulated_body(const S& scene, const T& t, const T* q, const T* qd, T* qdd) {
  using namespace detail;
  constexpr int NL = S::tree.n_links, N = S::n_q;
  const auto xf = joint_transforms(scene, q);
  const joint_state<T> xs{q, qd, N};
  std::array<Vec3<T>, NL> n_ext, f_ext;
  n_ext.fill(Vec3<T>::Zero());
  f_ext.fill(Vec3<T>::Zero());
  gather_external(scene, t, xs, xf, n_ext, f_ext);
  std::array<T, N> tau;
  joint_inputs(scene, t, xs, tau.data());
  std::array<Mat6<T>, NL> X, IA;
  std::array<Vec6<T>, NL> Sx, v, c, pA, U, a;
  std::array<T, NL> D, u;
  v[0].setZero();
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using XF = typename LI::template transform<T>;
    const auto& x = std::get<L - 1>(xf);
    Vec3<T> p = x.p();
    if constexpr (LI::has_offset) p += scene.model().set_offset[LI::parent_set].template cast<T>();
    X[L] = motion_transform<T>(x.matrix(), p);
    Sx[L].setZero();
    if constexpr (XF::rotates) Sx[L].template head<3>() = x.axis(T(1));
    else Sx[L].template tail<3>() = x.axis(T(1));
    const Vec6<T> vJ = Sx[L] * qd[LI::q];
    v[L] = X[L] * v[LI::parent] + vJ;
    c[L] = crm<T>(v[L]) * vJ;
    IA[L] = spatial_inertia<T>(scene.model().link[L]);
    Vec6<T> fext = Vec6<T>::Zero();
    fext.template head<3>() = n_ext[L];
    fext.template tail<3>() = f_ext[L];
    pA[L] = -crm<T>(v[L]).transpose() * (IA[L] * v[L]) - fext;
  });
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    U[L] = IA[L] * Sx[L];
    D[L] = Sx[L].dot(U[L]);
    u[L] = tau[LI::q] - Sx[L].dot(pA[L]);
    // The relative pivot test of solve_spd (newton_euler.hpp), against the
    // trace of the articulated inertia's block the joint moves in.
    using XF = typename LI::template transform<T>;
    const T scale = XF::rotates ? T(IA[L].template topLeftCorner<3, 3>().trace())
                                : T(IA[L].template bottomRightCorner<3, 3>().trace());
    if (!(D[L] > T(pivot_tolerance<N, T>()) * scale))
      throw simulation_error(concat("flange: singular articulated inertia at joint \"",
                                    S::table.names[LI::joint], "\" at t = ", static_cast<double>(t), ", ",
                                    describe_state(q, qd, N), ": pivot ", static_cast<double>(D[L]), " against ",
                                    static_cast<double>(scale)),
                             static_cast<double>(t));
    if constexpr (LI::parent != 0) {
      const Mat6<T> Ia = IA[L] - U[L] * U[L].transpose() / D[L];
      const Vec6<T> pa = pA[L] + Ia * c[L] + U[L] * (u[L] / D[L]);
      IA[LI::parent] += X[L].transpose() * Ia * X[L];
      pA[LI::parent] += X[L].transpose() * pa;
    }
  });
  a[0].setZero();
  if constexpr (S::has_gravity) a[0].template tail<3>() = -scene.gravity().template cast<T>();
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    const Vec6<T> ap = X[L] * a[LI::parent] + c[L];
    qdd[LI::q] = (u[L] - U[L].dot(ap)) / D[L];
    a[L] = ap + Sx[L] * qdd[LI::q];
  });
}

}  // namespace flange
