// Forward dynamics of a planar scene in planar arithmetic.
//
// A scene is planar, known from its types alone, when every revolute joint
// turns about one compile-time coordinate axis k and every prismatic joint
// slides along a compile-time coordinate axis other than k (and at least one
// joint is revolute). Then every link turns about k only, and the joint
// accelerations depend on in-plane quantities only:
//
//   - ω and ω̇ are scalars (their k components);
//   - a link origin's acceleration, the link force f, offsets p and first
//     moments h are 2-vectors in the plane (u, v) = ((k+1) mod 3, (k+2) mod 3);
//   - of the link torque only n_k matters, and (ω × I·ω)_k = 0, (I·ω̇)_k = I_kk·ω̇;
//   - of the rotational inertia only I_kk (about the link origin) matters.
//
// Out-of-plane offsets, products of inertia, gravity along k and torque
// components other than k change cut forces, never q̈: recover() still
// computes those in 3-D. The algorithms are those of newton_euler.hpp
// (Newton–Euler bias plus composite rigid bodies, LDLᵀ), with 2-D rotations:
//
//   (E·a)_u = c·a_u + s·a_v,  (E·a)_v = −s·a_u + c·a_v,   c = cos q, s = σ·sin q.
//
// tests/planar_test.cpp holds this against the spatial algorithm.
#pragma once
#include "flange/dynamics/newton_euler.hpp"

namespace flange {

namespace detail {

/// The plane's normal axis k if the scene is planar (see above), else −1.
template <class S>
constexpr bool t_is_revolute(int L) {
  bool r = false;
  [&]<int... I>(std::integer_sequence<int, I...>) {
    ((I + 1 == L ? (r = link_info<S, I + 1>::joint_type::type == joint_type::revolute) : false), ...);
  }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
  return r;
}

template <class S, int L>
constexpr std::pair<int, bool> link_axis() {  // (coordinate axis or −1, revolute)
  using J = typename link_info<S, L>::joint_type;
  if constexpr (J::axis_type::fixed) return {J::axis_type::index, J::type == joint_type::revolute};
  else return {-1, J::type == joint_type::revolute};
}
template <class S>
constexpr int planar_axis() {
  if constexpr (S::tree.n_links < 2) {
    return -1;
  } else {
    constexpr auto axes = []<int... L>(std::integer_sequence<int, L...>) {
      return std::array<std::pair<int, bool>, sizeof...(L)>{link_axis<S, L + 1>()...};
    }(std::make_integer_sequence<int, S::tree.n_links - 1>{});
    int k = -1;
    for (const auto& [axis, revolute] : axes)
      if (revolute) {
        if (axis < 0 || (k >= 0 && axis != k)) return -1;
        k = axis;
      }
    if (k < 0) return -1;
    for (const auto& [axis, revolute] : axes)
      if (!revolute && (axis < 0 || axis == k)) return -1;
    return k;
  }
}

/// What the planar algorithm knows of each link before any number is seen,
/// beyond link_flags: whether the origin's acceleration in the bias pass is
/// identically zero (no gravity reaches it and nothing above it turns), and
/// whether the joint's rotation is used at all (if not, no sin or cos).
template <class S>
struct planar_flags {
  static constexpr int NL = S::tree.n_links;
  struct table {
    std::array<bool, NL> ap_zero{};   ///< the parent origin's acceleration carried here is zero
    std::array<bool, NL> a_zero{};    ///< this origin's acceleration is zero
    std::array<bool, NL> need_rot{};  ///< the joint's 2-D rotation is used
  };
  static constexpr table value = [] {
    constexpr auto F = link_flags<S>::value;
    table t{};
    t.a_zero[0] = !S::has_gravity;
    for (int L = 1; L < NL; ++L) {
      const int P = S::tree.link_parent[L];
      const bool rev = S::tree.link_joint[L] >= 0 && t_is_revolute<S>(L);
      t.ap_zero[L] = t.a_zero[P] && (F.p_zero[L] || (F.wd_zero[P] && F.w_zero[P]));
      t.a_zero[L] = t.ap_zero[L] && (rev || F.w_zero[L]);
      t.need_rot[L] = rev && (!t.ap_zero[L] || P != 0);
    }
    return t;
  }();
};

template <class T>
struct vec2 {
  T u, v;
  friend vec2 operator+(const vec2& a, const vec2& b) { return {a.u + b.u, a.v + b.v}; }
  friend vec2 operator-(const vec2& a, const vec2& b) { return {a.u - b.u, a.v - b.v}; }
  friend vec2 operator*(const T& s, const vec2& a) { return {s * a.u, s * a.v}; }
  vec2& operator+=(const vec2& b) {
    u += b.u;
    v += b.v;
    return *this;
  }
};
/// (a × b)_k of two in-plane vectors.
template <class T>
T cross2(const vec2<T>& a, const vec2<T>& b) {
  return a.u * b.v - a.v * b.u;
}
/// (w·e_k) × a for an in-plane a.
template <class T>
vec2<T> perp(const T& w, const vec2<T>& a) {
  return {-w * a.v, w * a.u};
}

/// The in-plane part of a joint's motion: the 2-D rotation of a revolute
/// joint, or the in-plane axis of a prismatic one.
template <class S, int L, int K, class T>
struct planar_joint {
  using LI = link_info<S, L>;
  static constexpr bool revolute = LI::joint_type::type == joint_type::revolute;
  static constexpr int sigma = LI::dir > 0 ? 1 : -1;
  static constexpr int u = (K + 1) % 3, v = (K + 2) % 3;
  T c{1}, s{0}, q{0};
  explicit planar_joint(const T& qv) : q(qv) {
    if constexpr (revolute && planar_flags<S>::value.need_rot[L]) {
      using std::cos;
      using std::sin;
      c = cos(qv);
      s = sigma * sin(qv);
    }
  }
  /// parent coordinates → child coordinates
  vec2<T> rot(const vec2<T>& a) const {
    if constexpr (revolute) return {c * a.u + s * a.v, -s * a.u + c * a.v};
    else return a;
  }
  /// child coordinates → parent coordinates
  vec2<T> rot_t(const vec2<T>& a) const {
    if constexpr (revolute) return {c * a.u - s * a.v, s * a.u + c * a.v};
    else return a;
  }
  /// σ·n of a prismatic joint, in the plane: ±e_u or ±e_v.
  static vec2<T> axis() {
    constexpr int i = LI::joint_type::axis_type::index;
    return {T(i == u ? sigma : 0), T(i == v ? sigma : 0)};
  }
  /// σ·n·f for a prismatic joint.
  static T axis_dot(const vec2<T>& f) {
    constexpr int i = LI::joint_type::axis_type::index;
    if constexpr (i == u) return sigma * f.u;
    else return sigma * f.v;
  }
};

template <int K, class T>
vec2<T> in_plane(const Vec3d& x) {
  return {T(x((K + 1) % 3)), T(x((K + 2) % 3))};
}

template <class T>
struct planar_link {
  T w, wd;          // ω_k, ω̇_k (q̈ = 0)
  vec2<T> a, f, p;  // origin acceleration (with −g), link force, offset from the parent origin
  T n;              // n_k
};
/// Composite inertia in the plane: mass, first moment, I_kk about the origin.
template <class T>
struct planar_inertia {
  T m, I;
  vec2<T> h;
};

}  // namespace detail

/// q̈ = M⁻¹·(τ − b) at (t, q, q̇) for a planar scene, in planar arithmetic.
template <class S, class T>
void accelerations_planar(const S& scene, const T& t, const T* q, const T* qd, T* qdd) {
  constexpr int K = detail::planar_axis<S>();
  static_assert(K >= 0, "flange: accelerations_planar needs a planar scene (see flange/dynamics/planar.hpp)");
  constexpr int N = S::n_q, NL = S::tree.n_links;
  constexpr auto F = detail::link_flags<S>::value;
  using namespace detail;
  const auto xf = [&]<int... L>(std::integer_sequence<int, L...>) {
    return std::tuple<planar_joint<S, L + 1, K, T>...>{planar_joint<S, L + 1, K, T>(q[link_info<S, L + 1>::q])...};
  }(std::make_integer_sequence<int, NL - 1>{});
  const auto& model = scene.model();
  const joint_state<T> js{q, qd, N};

  // External loads on each link: torques about k and, from line and world
  // forces, in-plane forces. Those need the frames' positions, so a scene
  // with them runs the spatial position pass first (tree_walk.hpp).
  std::array<T, NL> n_ext{};
  std::array<vec2<T>, NL> f_ext{};
  if constexpr (has_motion_forces<S>()) {
    std::array<Vec3<T>, NL> n3, f3;
    gather_external(scene, t, js, joint_transforms(scene, q), n3, f3);
    for (int L = 1; L < NL; ++L) {
      if (F.has_ext[L]) n_ext[L] = n3[L](K);
      if (F.has_ext_f[L]) f_ext[L] = {f3[L]((K + 1) % 3), f3[L]((K + 2) % 3)};
    }
  } else {
    [&]<int... C>(std::integer_sequence<int, C...>) {
      (
          [&] {
            using Comp = typename S::template component_type<C>;
            if constexpr (Comp::kind == role::force && force_acts<S, C>()) {
              // A Torque's k component acts on frame_b's link and reacts on
              // frame_a's; rotations about k keep it.
              constexpr auto links = force_links<S, C>();
              const T Mk = scene.template component<C>().torque(t, js)(K);
              n_ext[links[1]] += Mk;
              n_ext[links[0]] -= Mk;
            }
          }(),
          ...);
    }(std::make_integer_sequence<int, S::n_components>{});
  }

  // Newton–Euler at q̈ = 0: the bias b.
  std::array<planar_link<T>, NL> lk;
  vec2<T> minus_g{T(0), T(0)};
  if constexpr (S::has_gravity) minus_g = T(-1) * in_plane<K, T>(scene.gravity());
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using PJ = planar_joint<S, L, K, T>;
    constexpr int P = LI::parent;
    const auto& x = std::get<L - 1>(xf);
    auto& c = lk[L];
    const auto& pl = lk[P];
    const T qdl = qd[LI::q];
    if constexpr (LI::has_offset) c.p = in_plane<K, T>(model.set_offset[LI::parent_set]);
    else c.p = {T(0), T(0)};
    if constexpr (!PJ::revolute) c.p += x.q * PJ::axis();
    // Terms are summed only where the flags say they exist: adding a zero the
    // compiler cannot see (IEEE: 0 + −0 = +0) would cost as much as any term.
    constexpr auto PF = planar_flags<S>::value;
    constexpr bool base = P == 0 ? S::has_gravity : !PF.a_zero[P];
    constexpr bool t_wd = !F.p_zero[L] && !F.wd_zero[P], t_w = !F.p_zero[L] && !F.w_zero[P];
    vec2<T> ap;
    if constexpr (base) {
      if constexpr (P == 0) ap = minus_g;
      else ap = pl.a;
    }
    if constexpr (t_wd) accumulate<base>(ap, perp(pl.wd, c.p));
    if constexpr (t_w) accumulate<base || t_wd>(ap, (-pl.w * pl.w) * c.p);
    if constexpr (PJ::revolute) {
      c.w = PJ::sigma * qdl;
      if constexpr (!F.w_zero[P]) c.w += pl.w;
      if constexpr (!F.wd_zero[P]) c.wd = pl.wd;
      if constexpr (!PF.a_zero[L]) c.a = x.rot(ap);
    } else {
      if constexpr (!F.w_zero[L]) c.w = pl.w;
      if constexpr (!F.wd_zero[L]) c.wd = pl.wd;
      if constexpr (!PF.ap_zero[L]) c.a = ap;
      if constexpr (!F.w_zero[L]) accumulate<!PF.ap_zero[L]>(c.a, perp(T(2) * c.w, qdl * PJ::axis()));
    }
    const auto& I = model.link[L];
    const vec2<T> h = in_plane<K, T>(I.h);
    // f = m·a + ω̇ × h − ω²·h and n = h × a + I_kk·ω̇ (zero where the flags say).
    constexpr bool f_a = !PF.a_zero[L], f_wd = !F.wd_zero[L], f_w = !F.w_zero[L];
    if constexpr (F.need_f[L]) {
      constexpr bool g_wd = f_wd && !F.h_zero[L], g_w = f_w && !F.h_zero[L];
      if constexpr (f_a) c.f = T(I.m) * c.a;
      if constexpr (g_wd) accumulate<f_a>(c.f, perp(c.wd, h));
      if constexpr (g_w) accumulate<f_a || g_wd>(c.f, (-c.w * c.w) * h);
      if constexpr (!(f_a || g_wd || g_w)) c.f = {T(0), T(0)};
      if constexpr (F.has_ext_f[L]) c.f = c.f - f_ext[L];
    }
    constexpr bool n_a = f_a && !F.h_zero[L], n_wd = f_wd && F.I_kind[L] > 0;
    if constexpr (n_a) c.n = cross2(h, c.a);
    if constexpr (n_wd) accumulate<n_a>(c.n, T(I.I(K, K)) * c.wd);
    if constexpr (!(n_a || n_wd)) c.n = T(0);
    if constexpr (F.has_ext[L]) c.n -= n_ext[L];
  });
  std::array<T, N> r;
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using PJ = planar_joint<S, L, K, T>;
    const auto& x = std::get<L - 1>(xf);
    auto& c = lk[L];
    if constexpr (PJ::revolute) r[LI::q] = -(PJ::sigma * c.n);
    else r[LI::q] = -PJ::axis_dot(c.f);
    if constexpr (LI::parent != 0) {
      auto& P = lk[LI::parent];
      const vec2<T> fp = x.rot_t(c.f);
      if constexpr (F.need_f[LI::parent]) P.f += fp;
      P.n += c.n;
      if constexpr (!F.p_zero[L]) P.n += cross2(c.p, fp);
    }
  });
  std::array<T, N> tau;
  joint_inputs(scene, t, js, tau.data());
  for (int i = 0; i < N; ++i) r[i] += tau[i];

  // Composite rigid bodies: the mass matrix.
  Eigen::Matrix<T, N, N> M;
  std::array<T, N> scale;  // what each diagonal entry is before cancellation: I_kk or m
  zero_branch_pairs<S>(M);
  std::array<planar_inertia<T>, NL> ic;
  for_links<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    const auto& I = model.link[L];
    ic[L] = {T(I.m), T(I.I(K, K)), in_plane<K, T>(I.h)};
  });
  for_links_reverse<S>([&](auto l) {
    constexpr int L = decltype(l)::value;
    using LI = link_info<S, L>;
    using PJ = planar_joint<S, L, K, T>;
    const auto& c = ic[L];
    // F = Ic·S: revolute S = σ·e_k → (n, f) = (σ·I, σ·e_k × h); prismatic
    // S = σ·n → (h × σn, m·σn).
    T n;
    vec2<T> f;
    if constexpr (PJ::revolute) {
      n = PJ::sigma * c.I;
      f = perp(T(PJ::sigma), c.h);
      M(LI::q, LI::q) = scale[LI::q] = c.I;
    } else {
      f = c.m * PJ::axis();
      n = cross2(c.h, PJ::axis());
      M(LI::q, LI::q) = scale[LI::q] = c.m;
    }
    // Carry F up through the ancestors, projecting on each joint's axis.
    auto carry = [&](auto self, auto j, T nn, vec2<T> ff) -> void {
      constexpr int J = decltype(j)::value;
      using LJ = link_info<S, J>;
      constexpr int P = LJ::parent;
      if constexpr (P != 0) {
        const vec2<T> fp = std::get<J - 1>(xf).rot_t(ff);
        T np = nn;
        if constexpr (!F.p_zero[J]) np += cross2(lk[J].p, fp);
        using PP = planar_joint<S, P, K, T>;
        T v;
        if constexpr (PP::revolute) v = PP::sigma * np;
        else v = PP::axis_dot(fp);
        M(link_info<S, P>::q, LI::q) = v;
        M(LI::q, link_info<S, P>::q) = v;
        self(self, std::integral_constant<int, P>{}, np, fp);
      }
    };
    carry(carry, std::integral_constant<int, L>{}, n, f);
    if constexpr (LI::parent != 0) {
      auto& pc = ic[LI::parent];
      const vec2<T> h = std::get<L - 1>(xf).rot_t(c.h);
      pc.m += c.m;
      pc.h += h;
      pc.I += c.I;
      if constexpr (!F.p_zero[L]) {
        const vec2<T>& p = lk[L].p;
        pc.h += c.m * p;
        pc.I += T(2) * (p.u * h.u + p.v * h.v) + c.m * (p.u * p.u + p.v * p.v);
      }
    }
  });
  if (const auto pivot = solve_spd<N>(M, r.data(), qdd, scale.data()); pivot.index >= 0) [[unlikely]]
    singular_mass_matrix<S>(pivot, t, q, qd, N);
}

}  // namespace flange
