// The loops' constraint rows and their derivatives in q, from the tree's
// motions in doubles: G (Φ̇ = G·v) and C = G·v̇ + Ġ·v (Φ̈ at the rates v and
// accelerations v̇), each with its derivative along q's directions, a dual
// number's lanes (simulate/jacobian.hpp's implicit differentiation of the
// constrained accelerations).
//
// Everything is in the World's axes at its origin (spatial vectors, angular
// part first; in a planar scene the plane's three numbers, derivatives.hpp's
// geometry_t, where every motion of the tree stays), over the passes' nodes (dynamics/derivatives.hpp: one per
// rate; a joint of rates in series is as many nodes in a row). Node n's
// column s_n, velocity V_n = V_p + s_n·v_n and acceleration A_n = A_p +
// s_n·v̇_n + V_p × s_n·v_n (p its parent node; no gravity: the rows are
// kinematic). Moving q_j turns node j's subtree, relative to j's parent
// node p, by s_j; so for node n at or below j
//
//   ∂V_n/∂q_j = s_j × (V_n − V_p)
//   ∂A_n/∂q_j = s_j × (A_n − A_p) − (s_j × V_p) × (V_n − V_p)
//   ∂s_n/∂q_j = s_j × s_n                  (n strictly below j)
//
// and a point or an axis fixed in n's link moves by s_j (x: ω_j × x + v_j,
// e: ω_j × e). Those derivatives seed the two frames of each cut, in dual
// numbers of one lane per direction of q; the cut's rows (loops.hpp's
// cut_constraint, the rows' one definition) then run in dual numbers on the
// two frames alone, no pass over the tree in dual numbers. Row e's entry for
// rate i is ρ·s_i, ρ = (n + x × f, f) the row's coefficients on the frame's
// angular velocity and origin velocity taken to the World's origin, for each
// frame whose link node i moves; its derivative the product rule's two
// terms.
//
// On the planar four-bar this takes the Jacobian from 4.8 to 3.7
// derivatives, where the loops' kinematics ran in dual numbers through the
// whole tree (tools/probes/loop_scenes_jacobian.cpp; docs/performance.md).
// Where: a tree whose coordinates are its rates (no ball: a ball's
// quaternion is not its rates' coordinate), simulate/jacobian.hpp's
// loops_take_passes.
#pragma once
#include <array>

#include "flange/detail/inline.hpp"
#include "flange/dynamics/derivatives.hpp"
#include "flange/dynamics/loops.hpp"
#include "flange/math/sparse.hpp"

namespace flange::detail {

/// A spatial vector in the World's axes at its origin, in the scene's
/// geometry (derivatives.hpp's geometry_t: in a planar scene the plane's
/// three numbers, which every motion of the tree stays in).
template <class S>
using world_motion = spatial<geometry_t<S>>;
template <class G>
FLANGE_INLINE spatial<G> operator^(const spatial<G>& x, const spatial<G>& y) {
  return motion_cross(x, y);
}
/// A geometry's angular and linear parts as 3-vectors.
template <class G>
FLANGE_INLINE Vec3d ang_in_space(const typename G::ang& w) {
  if constexpr (std::is_same_v<G, space>) return w;
  else return Vec3d::Unit(3 - G::A - G::B) * w;
}
template <class G>
FLANGE_INLINE Vec3d lin_in_space(const typename G::lin& l) {
  if constexpr (std::is_same_v<G, space>) {
    return l;
  } else {
    Vec3d r = Vec3d::Zero();
    r[G::A] = l[0];
    r[G::B] = l[1];
    return r;
  }
}

/// The tree's nodes' columns, velocities and accelerations (at v̇, without
/// gravity) and its links' poses, at (q, v, v̇).
template <class S>
struct loop_motion_state {
  static constexpr int NN = S::n_v + 1, NL = S::tree.n_links;
  std::array<world_motion<S>, NN> s, V, A;
  std::array<Mat3d, NL> R;  ///< rotates the World into link L's axes
  std::array<Vec3d, NL> r;  ///< link L's origin
};

/// The node of each rate (derivative_nodes' rate, inverted).
template <class S>
inline constexpr auto node_of_rate = [] {
  std::array<int, S::n_v> r{};
  for (int n = 1; n <= S::n_v; ++n) r[derivative_nodes<S>::table.rate[n]] = n;
  return r;
}();

/// Whether node j is node n or one of its ancestors.
template <class S>
inline constexpr auto node_at_or_above = [] {
  using nodes = derivative_nodes<S>;
  constexpr int NN = S::n_v + 1;
  std::array<std::array<bool, NN>, NN> r{};
  for (int n = 1; n < NN; ++n)
    for (int j = n; j != 0; j = nodes::table.parent[j]) r[j][n] = true;
  return r;
}();

/// Whether node n moves a frame of some cut (it is at or above the link
/// of one).
template <class S>
inline constexpr auto nodes_moving_cuts = [] {
  constexpr int NN = S::n_v + 1;
  std::array<bool, NN> r{};
  auto mark = [&](int link) {
    if (link != 0)
      for (int i = 1; i < NN; ++i) r[i] = r[i] || node_at_or_above<S>[i][derivative_nodes<S>::table.last[link]];
  };
  [&]<int... K>(std::integer_sequence<int, K...>) {
    ((mark(cut_info<S, K>::link_a), mark(cut_info<S, K>::link_b)), ...);
  }(std::make_integer_sequence<int, S::tree.n_cuts>{});
  return r;
}();

/// The lanes of a dual number type.
template <class D>
struct lanes_of;
template <int N>
struct lanes_of<dual<double, N>> {
  static constexpr int value = N;
};

/// The nodes' columns, velocities and accelerations (at v̇, no gravity) and
/// the links' poses at (q, v, v̇), into st.
template <class S>
void loop_motions(const S& scene, const double* q, const double* v, const double* vdot, loop_motion_state<S>& st) {
  using nodes = derivative_nodes<S>;
  using G = geometry_t<S>;
  constexpr int K = planar_axis<S>();
  const auto motions = link_motions<spatial_algebra, double, true>(scene, q);
  const auto poses = link_poses<S, double>(motions, v);
  st.R[0].setIdentity();
  st.r[0].setZero();
  for_links<S>([&](auto l) FLANGE_INLINE_LAMBDA {
    constexpr int L = decltype(l)::value;
    constexpr int nv = link_info<S, L>::nv, first = nodes::table.last[L] - nv + 1;
    const auto& m = std::get<L - 1>(motions);
    const auto& P = poses[L];
    st.R[L] = P.R;
    st.r[L] = P.r;
    static_for<nv>([&](auto k) FLANGE_INLINE_LAMBDA {
      const auto c = m.template col<decltype(k)::value>();
      const Vec3d w = rot_t(typed_rotation<K>(P), c.ang).dense(), u = rot_t(typed_rotation<K>(P), c.lin).dense();
      st.s[first + k] = {G::ang_of(w), G::lin_of(plus(u, cross(P.r, w)))};
    });
  });
  st.V[0] = st.A[0] = {G::zero_ang(), G::lin::Zero()};
  for (int n = 1; n < S::n_v + 1; ++n) {
    const int p = nodes::table.parent[n], i = nodes::table.rate[n];
    st.V[n] = st.V[p] + st.s[n] * v[i];
    st.A[n] = st.A[p] + st.s[n] * vdot[i] + (st.V[p] ^ st.s[n]) * v[i];
  }
}

/// A dual number's 3-vector from its value and its lanes.
template <class D, int W>
FLANGE_INLINE Vec3<D> with_lanes3(const Vec3d& value, const std::array<Vec3d, W>& d) {
  Vec3<D> r;
  for (int k = 0; k < 3; ++k) r[k] = D::with_lanes(value[k], [&](int l) { return d[l][k]; });
  return r;
}

/// Cut frame Set's motion (loops.hpp's set_motion) in dual numbers D whose
/// lane l is the derivative along q's direction first + l.
template <class S, int Set, class D>
set_motion<D> frame_lanes(const S& scene, const loop_motion_state<S>& st, int first) {
  using nodes = derivative_nodes<S>;
  using G = geometry_t<S>;
  constexpr int L = S::tree.set_link[Set], W = lanes_of<D>::value;
  const Vec3d o = scene.model().set_offset[Set];
  set_motion<D> f;
  if constexpr (L == 0) {
    if constexpr (set_rotation_kind<S>(Set) == -2) f.R = Mat3<D>::Identity();
    else f.R = scene.model().set_rotation[Set].template cast<D>();
    f.r = o.cast<D>();
    f.v = f.w = f.wd = f.a = Vec3<D>::Zero();
    return f;
  } else {
    constexpr int n = nodes::table.last[L];
    Mat3d R;
    if constexpr (set_rotation_kind<S>(Set) == -2) R = st.R[L];
    else R = small::mul(Mat3d(scene.model().set_rotation[Set]), st.R[L]);
    const Vec3d x = plus(st.r[L], st.R[L].transpose() * o);
    const auto xg = G::lin_of(x);
    const world_motion<S>&V = st.V[n], &A = st.A[n];
    // The frame's origin's velocity and acceleration from its link's.
    const auto& w = V.a;
    const auto& wd = A.a;
    const auto vx = plus(V.l, cross(w, xg));
    const auto ax = plus(plus(A.l, cross(wd, xg)), cross(w, vx));
    // Each lane's derivatives of them, of the origin and of the frame's
    // axes (R's rows, World coordinates).
    std::array<Vec3d, W> dx, dw, dv, dwd, da;
    std::array<std::array<Vec3d, W>, 3> de;
    for (int l = 0; l < W; ++l) {
      const int c = first + l;
      const int j = c < S::n_v ? node_of_rate<S>[c] : 0;
      if (j == 0 || !node_at_or_above<S>[j][n]) {
        dx[l] = dw[l] = dv[l] = dwd[l] = da[l] = de[0][l] = de[1][l] = de[2][l] = Vec3d::Zero();
        continue;
      }
      const int p = nodes::table.parent[j];
      const world_motion<S>& s = st.s[j];
      const world_motion<S> rel = V - st.V[p];
      const world_motion<S> dV = s ^ rel, dA = (s ^ (A - st.A[p])) - ((s ^ st.V[p]) ^ rel);
      const auto dxg = plus(cross(s.a, xg), s.l);
      const auto dvg = plus(plus(dV.l, cross(dV.a, xg)), cross(w, dxg));
      const auto dag = plus(plus(plus(dA.l, cross(dA.a, xg)), cross(wd, dxg)), plus(cross(dV.a, vx), cross(w, dvg)));
      dx[l] = lin_in_space<G>(dxg);
      dw[l] = ang_in_space<G>(dV.a);
      dv[l] = lin_in_space<G>(dvg);
      dwd[l] = ang_in_space<G>(dA.a);
      da[l] = lin_in_space<G>(dag);
      const Vec3d sa = ang_in_space<G>(s.a);
      for (int i = 0; i < 3; ++i) de[i][l] = cross(sa, Vec3d(R.row(i).transpose()));
    }
    for (int i = 0; i < 3; ++i) f.R.row(i) = with_lanes3<D, W>(R.row(i).transpose(), de[i]).transpose();
    f.r = with_lanes3<D, W>(x, dx);
    f.w = with_lanes3<D, W>(ang_in_space<G>(w), dw);
    f.v = with_lanes3<D, W>(lin_in_space<G>(vx), dv);
    f.wd = with_lanes3<D, W>(ang_in_space<G>(wd), dwd);
    f.a = with_lanes3<D, W>(lin_in_space<G>(ax), da);
    return f;
  }
}

/// The loops' G and C (C = G·v̇ + Ġ·v at loop_motions' v̇) in dual numbers
/// D, lane l the derivative along q's direction first + l.
template <class S, class D>
struct loop_lanes {
  static constexpr int m = n_constraints<S>(), nv = S::n_v;
  std::array<D, m> C;
  std::array<std::array<D, nv>, m> G;
};
template <class S, class D>
void loop_rows_lanes(const S& scene, const loop_motion_state<S>& st, int first, loop_lanes<S, D>& out) {
  using nodes = derivative_nodes<S>;
  using G = geometry_t<S>;
  constexpr int m = n_constraints<S>(), NN = S::n_v + 1, W = lanes_of<D>::value;
  for (auto& row : out.G) row.fill(D(0.0));
  // The columns of the nodes that move some cut's frame, and their lanes
  // ∂s_i/∂q_j = s_j × s_i (j strictly above i).
  constexpr auto& moves_a_cut = nodes_moving_cuts<S>;
  std::array<std::array<world_motion<S>, W>, NN> ds;
  for (int i = 1; i < NN; ++i) {
    if (!moves_a_cut[i]) continue;
    for (int l = 0; l < W; ++l) {
      const int k = first + l;
      const int j = k < S::n_v ? node_of_rate<S>[k] : 0;
      ds[i][l] = j != 0 && j != i && node_at_or_above<S>[j][i] ? st.s[j] ^ st.s[i]
                                                                : world_motion<S>{G::zero_ang(), G::lin::Zero()};
    }
  }
  std::array<constraint_row<D>, m> rows;
  for_cuts<S>([&](auto k) FLANGE_INLINE_LAMBDA {
    constexpr int K = decltype(k)::value;
    using CI = cut_info<S, K>;
    if constexpr (CI::rows > 0) {
      const auto a = frame_lanes<S, CI::set_a, D>(scene, st, first);
      const auto b = frame_lanes<S, CI::set_b, D>(scene, st, first);
      cut_constraint<S, K>(scene, a, b, rows.data());
      for (int e = cut_row<S, K>(); e < cut_row<S, K>() + CI::rows; ++e) {
        const auto& w = rows[e];
        out.C[e] = w.bias;
        // ρ = (n + x × f, f) on each frame, and its lanes; row e's entry
        // ρ·s_i for the nodes i that move the frame's link.
        auto add = [&](int link, const Vec3<D>& n, const Vec3<D>& f, const Vec3<D>& x) FLANGE_INLINE_LAMBDA {
          if (link == 0) return;
          auto value = [](const Vec3<D>& y) { return Vec3d(y[0].v, y[1].v, y[2].v); };
          auto lane = [](const Vec3<D>& y, int l) { return Vec3d(y[0].d[l], y[1].d[l], y[2].d[l]); };
          const Vec3d fv = value(f), xv = value(x);
          const world_motion<S> rho{G::ang_of(plus(value(n), cross(xv, fv))), G::lin_of(fv)};
          std::array<world_motion<S>, W> drho;
          for (int l = 0; l < W; ++l) {
            const Vec3d fl = lane(f, l);
            drho[l] = {G::ang_of(plus(lane(n, l), plus(cross(lane(x, l), fv), cross(xv, fl)))), G::lin_of(fl)};
          }
          for (int i = 1; i < NN; ++i) {
            if (!node_at_or_above<S>[i][nodes::table.last[link]]) continue;
            const world_motion<S>& si = st.s[i];
            out.G[e][nodes::table.rate[i]] += D::with_lanes(rho.dot(si), [&](int l) {
              return drho[l].dot(si) + rho.dot(ds[i][l]);
            });
          }
        };
        add(CI::link_a, w.wa, w.va, a.r);
        add(CI::link_b, w.wb, w.vb, b.r);
      }
    }
  });
}

}  // namespace flange::detail
