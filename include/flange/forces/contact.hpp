// Contact: compliant contact between two shapes, one attached at each frame,
// with Hunt–Crossley's normal force and Coulomb friction on a Stribeck
// curve, in the form of Simbody's HuntCrossleyForce.
//
//   Contact<"foot_ground", contact_shape::sphere, contact_shape::half_space>(
//       {.a = {.radius = 0.02}, .b = {.n = {0, 1, 0}},
//        .material_a = {.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7},
//        .material_b = {.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7}})
//
// Shape a sits at frame_a, shape b at frame_b (contact_geometry.hpp: the
// shapes, the pairs, and where a pair overlaps: at one point, or at a
// capsule's two ends, or a box's eight corners). Which shapes can touch is
// written in the scene, one Contact per pair; shapes that no Contact pairs
// pass through each other.
//
// At each point of a pair, with δ the penetration (the overlap of the shapes
// along N, the normal from b toward a), δ̇ its rate, R the effective radius
// (a sphere's radius against a half-space or a box, r_a·r_b/(r_a + r_b)
// between spheres), and the materials combined as Simbody combines them
// (k_i = E_i^(2/3), s = k_a/(k_a + k_b), k = k_b·s, c = c_b·s + c_a·(1 − s),
// μ = 2·μ_a·μ_b/(μ_a + μ_b)):
//
//   f_H = (4/3)·k·δ·√(R·k·δ)           Hertz (= (4/3)·E·√R·δ^(3/2), E = k^(3/2))
//   f_n = max(0, f_H·(1 + (3/2)·c·δ̇))  Hunt–Crossley: pushes, never pulls
//   f_t = f_n·(min(v_s/v_t, 1)·(μ_d + 2·(μ_s − μ_d)/(1 + (v_s/v_t)²)) + μ_v·v_s)
//
// f_t opposes the slip velocity v_s of a on b at the contact point p, which
// lies at the middle of the overlap, moved by δ·(1/2 − s) along N (toward
// the softer surface). The stored energy is (2/5)·f_H·δ. Unlike Simbody, the
// friction is f_n's (never pushing when the normal force would pull).
//
// f_n grows like δ^(3/2) from first touch, so the force is C¹ in the state;
// the friction's slope jumps at v_s = v_t. A scene without a Contact has none
// of this arithmetic. The element's internal variables are, per point, δ,
// f_n, f_t, v_s and p (recover(…)["foot_ground.δ"], …; a pair of several
// points numbers them: "δ[0]", "f_n[0]", … "p[7]").
#pragma once
#include <algorithm>
#include <cmath>
#include <string_view>
#include <tuple>
#include <utility>
#include <type_traits>

#include <boost/hana/flatten.hpp>
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/forces/contact_geometry.hpp"

namespace flange {

/// A contact surface's material (Simbody's HuntCrossleyForce::setBodyParameters).
struct contact_material {
  double stiffness = 1e7;        ///< E, the plane-strain modulus [Pa]
  double dissipation = 0;        ///< c [s/m]: the coefficient of restitution is about 1 − c·v at impact speed v
  double static_friction = 0;    ///< μ_s
  double dynamic_friction = 0;   ///< μ_d
  double viscous_friction = 0;   ///< μ_v [s/m]
};

namespace diagnostic {
template <class A, class B>
struct contact_pair_not_supported {
  static_assert(always_false<A>,
                "flange: Contact pairs sphere-half_space, sphere-sphere, sphere-box, capsule-half_space and "
                "box-half_space (shape a at frame_a, shape b at frame_b); this pair of shapes (the template "
                "arguments) is not supported: swap frame_a and frame_b if the other order is listed "
                "(box-box, cylinders and meshes are not there yet, docs/contact.md)");
};
}  // namespace diagnostic

namespace detail {
/// A contact's numbers at one point at one instant (world coordinates).
template <class T>
struct contact_point {
  T depth{0}, depth_rate{0}, fn{0}, ft{0}, vs{0}, hertz{0};
  Vec3<T> point = Vec3<T>::Zero();  ///< where the force acts (apart: the point of b's surface nearest a)
  Vec3<T> force = Vec3<T>::Zero();  ///< on frame_a's side; frame_b's side takes −force
};

/// The names of a contact's internals: per point δ, f_n, f_t, v_s, p; with
/// several points numbered "δ[0]" …
inline constexpr std::string_view contact_internal_names[5][9] = {
    {"δ", "δ[0]", "δ[1]", "δ[2]", "δ[3]", "δ[4]", "δ[5]", "δ[6]", "δ[7]"},
    {"f_n", "f_n[0]", "f_n[1]", "f_n[2]", "f_n[3]", "f_n[4]", "f_n[5]", "f_n[6]", "f_n[7]"},
    {"f_t", "f_t[0]", "f_t[1]", "f_t[2]", "f_t[3]", "f_t[4]", "f_t[5]", "f_t[6]", "f_t[7]"},
    {"v_s", "v_s[0]", "v_s[1]", "v_s[2]", "v_s[3]", "v_s[4]", "v_s[5]", "v_s[6]", "v_s[7]"},
    {"p", "p[0]", "p[1]", "p[2]", "p[3]", "p[4]", "p[5]", "p[6]", "p[7]"}};
inline constexpr std::string_view contact_quantity_names[5] = {"contact_depth", "contact_f_n", "contact_f_t",
                                                               "contact_v_s", "contact_point"};
inline constexpr std::string_view contact_flow_names[4] = {"contact_F_a", "contact_M_a", "contact_F_b",
                                                           "contact_M_b"};
}  // namespace detail

template <fixed_string Name, class ShapeA, class ShapeB>
class Contact {
  static constexpr bool supported = detail::contact_pair<ShapeA, ShapeB>::supported;
  /// An unsupported pair is one diagnostic; the rest compiles as a sphere on a half-space.
  using pair_type = std::conditional_t<supported, detail::contact_pair<ShapeA, ShapeB>,
                                       detail::contact_pair<contact_shape::sphere, contact_shape::half_space>>;
  static constexpr int M = pair_type::points;
  static constexpr int per_point = 5;

 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Contact";
  static constexpr role kind = role::force;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  /// The points where the pair can touch: 1, a capsule's 2 ends, or a box's 8 corners.
  static constexpr int points = M;
  static constexpr auto internals = [] {
    std::array<internal_decl, per_point * M> d{};
    for (int i = 0; i < M; ++i)
      for (int j = 0; j < per_point; ++j)
        d[per_point * i + j] = {detail::contact_internal_names[j][M == 1 ? 0 : i + 1],
                                j == 4 ? expr::var_kind::vec : expr::var_kind::scalar};
    return d;
  }();
  /// Needs the frames' positions and velocities (a position pass in the dynamics).
  static constexpr bool needs_motion = true;
  static constexpr bool line_of_action = false;
  /// Its frames must lie on two bodies (scene.hpp checks).
  static constexpr bool pairs_two_bodies = true;
  /// A force at each contact point: a force and a torque about each frame's origin.
  static constexpr bool exerts_force = true, exerts_torque = true;
  /// Its loads read its frames' motions alone, not the joint state.
  static constexpr bool reads_state = false;

  struct params {
    ShapeA a{};                           ///< the shape at frame_a
    ShapeB b{};                           ///< the shape at frame_b
    contact_material material_a{};        ///< shape a's surface
    contact_material material_b{};        ///< shape b's surface
    double transition_velocity = 1e-3;    ///< v_t [m/s]: static friction peaks at this slip speed
  };

  explicit Contact(params p) {
    if constexpr (supported) {
      geometry_ = {p.a, p.b};
      detail::check_pair(name.view(), geometry_);
      for (int i = 0; i < M; ++i) reff_[i] = geometry_.radius(i);
      if constexpr (against_half_space)
        for (int i = 0; i < M; ++i) center_[i] = geometry_.center(i);
    } else {
      (void)sizeof(diagnostic::contact_pair_not_supported<ShapeA, ShapeB>);
    }
    check_material("material_a", p.material_a);
    check_material("material_b", p.material_b);
    detail::require_finite(name.view(), type_name, "transition_velocity", p.transition_velocity);
    if (!(p.transition_velocity > 0))
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": transition_velocity = ",
                                           p.transition_velocity, " must be positive"));
    using std::cbrt;
    const double ka = cbrt(p.material_a.stiffness * p.material_a.stiffness);
    const double kb = cbrt(p.material_b.stiffness * p.material_b.stiffness);
    s_ = ka / (ka + kb);
    k_ = kb * s_;
    c_ = p.material_b.dissipation * s_ + p.material_a.dissipation * (1 - s_);
    auto mix = [](double x, double y) { return x + y > 0 ? 2 * x * y / (x + y) : 0.0; };
    mu_s_ = mix(p.material_a.static_friction, p.material_b.static_friction);
    mu_d_ = mix(p.material_a.dynamic_friction, p.material_b.dynamic_friction);
    mu_v_ = mix(p.material_a.viscous_friction, p.material_b.viscous_friction);
    inv_vt_ = 1 / p.transition_velocity;
  }

  /// The pair's shapes, as given.
  [[nodiscard]] const pair_type& geometry() const { return geometry_; }

  /// The contact at point i for the two frames' motion (frame_kinematics: R
  /// turns world into the frame, w in frame coordinates).
  template <class T>
  [[nodiscard]] FLANGE_INLINE detail::contact_point<T> evaluate(int i, const frame_kinematics<T>& a,
                                                  const frame_kinematics<T>& b) const {
    detail::contact_point<T> cp;
    const auto o = geometry_.overlap(i, a, b);
    const Vec3<T>& N = o.N;
    if (!(o.depth > T(0))) {
      cp.point = o.surface;
      return cp;
    }
    cp.depth = o.depth;
    // The middle of the overlap, moved toward the softer side.
    cp.point = o.surface - (T(s_) * cp.depth) * N;
    // The velocity of b relative to a at that point.
    // (ω in world coordinates as plain vectors: g++ calls Eigen's cross of a
    // product expression out of line.)
    const Vec3<T> wa = a.R.transpose() * a.w, wb = b.R.transpose() * b.w;
    const Vec3<T> da = cp.point - a.r, db = cp.point - b.r;
    const Vec3<T> va = a.v + wa.cross(da);
    const Vec3<T> vb = b.v + wb.cross(db);
    const Vec3<T> v = vb - va;
    cp.depth_rate = v.dot(N);
    const Vec3<T> vt = v - cp.depth_rate * N;
    const auto l = law(i, cp.depth, cp.depth_rate, vt.squaredNorm());
    cp.hertz = l.hertz;
    cp.fn = l.fn;
    cp.vs = l.vs;
    cp.ft = l.g * l.vs;
    cp.force = l.fn * N + l.g * vt;
    return cp;
  }

  /// Whether shape b is a half-space: at rest in the World, it is met in the
  /// coordinates of frame_a's link (half_space_loads).
  static constexpr bool against_half_space = std::is_same_v<ShapeB, contact_shape::half_space>;

  /// What a half-space at rest in the World exerts on frame_a's link, added
  /// to f and n (link coordinates, the torque about the link's origin): the
  /// same law as evaluate's, with no world pose of the points and nothing to
  /// turn back. n_L: the half-space's outward normal in link coordinates;
  /// h: the link origin's height above the half-space's surface; v_L, w_L:
  /// the origin's velocity and ω, link coordinates; the frame sits at p in
  /// its link, turned by Rs (link into frame coordinates) when Turned.
  template <bool Turned, class T>
  FLANGE_INLINE void half_space_loads(const Vec3<T>& n_L, const T& h, const Vec3<T>& v_L, const Vec3<T>& w_L,
                                      const Vec3d& p, const Mat3d& Rs, Vec3<T>& f, Vec3<T>& n) const
    requires against_half_space
  {
    for (int i = 0; i < M; ++i) {
      Vec3d c = p;  // the point's sphere centre, link coordinates
      if constexpr (Turned) c.noalias() += Rs.transpose() * center_[i];
      else c += center_[i];
      const T n0 = n_L[0], n1 = n_L[1], n2 = n_L[2], c0 = c[0], c1 = c[1], c2 = c[2];
      const T gap = h + (n0 * c0 + n1 * c1 + n2 * c2);
      const T depth = T(reff_[i]) - gap;
      if (!(depth > T(0))) continue;
      // The contact point d = c − e·n from the link's origin, and the
      // ground's velocity relative to it, −(v + ω × d) = e·(ω × n) − (v + ω × c):
      // written so, the parts that do not wait for the overlap (v + ω × c,
      // ω × n and the depth rate −(v + ω × c)·n, as (ω × n)·n = 0) are
      // computed beside it, not after it. All in scalars: this is the path
      // from the state to the accelerations, and on it Eigen's 16-byte
      // packets over three entries (their shuffles, and their loads of
      // values just stored entry by entry) made a ball's pair 38 ns where
      // it is 28 in scalars (docs/contact.md, "Cost").
      const T e = gap + T(s_) * depth;
      const T w0 = w_L[0], w1 = w_L[1], w2 = w_L[2];
      const T vc0 = v_L[0] + (w1 * c2 - w2 * c1), vc1 = v_L[1] + (w2 * c0 - w0 * c2),
              vc2 = v_L[2] + (w0 * c1 - w1 * c0);
      const T rate = -(vc0 * n0 + vc1 * n1 + vc2 * n2);
      // The slip velocity: the relative velocity less its normal part.
      const T vt0 = e * (w1 * n2 - w2 * n1) - vc0 - rate * n0, vt1 = e * (w2 * n0 - w0 * n2) - vc1 - rate * n1,
              vt2 = e * (w0 * n1 - w1 * n0) - vc2 - rate * n2;
      const auto l = law(i, depth, rate, vt0 * vt0 + vt1 * vt1 + vt2 * vt2);
      const T F0 = l.fn * n0 + l.g * vt0, F1 = l.fn * n1 + l.g * vt1, F2 = l.fn * n2 + l.g * vt2;
      const T d0 = c0 - e * n0, d1 = c1 - e * n1, d2 = c2 - e * n2;
      f[0] += F0;
      f[1] += F1;
      f[2] += F2;
      n[0] += d1 * F2 - d2 * F1;
      n[1] += d2 * F0 - d0 * F2;
      n[2] += d0 * F1 - d1 * F0;
    }
  }

  /// The deepest overlap of its points (0 where apart): a breakdown check
  /// compares it with the smaller shape's size, geometry().size().
  [[nodiscard]] double deepest(const frame_kinematics<double>* k) const {
    double d = 0;
    for (int i = 0; i < M; ++i) d = std::max(d, geometry_.overlap(i, k[0], k[1]).depth);
    return d;
  }

  /// What the element exerts on the rest of the scene at each of its frames:
  /// force and torque (about the frame's origin), world coordinates.
  template <class T>
  FLANGE_INLINE void wrenches(const T&, const state_of<T> auto&, const frame_kinematics<T>* k, wrench<T>* on) const {
    Vec3<T> F = Vec3<T>::Zero(), Ma = Vec3<T>::Zero();
    for (int i = 0; i < M; ++i) {
      const auto cp = evaluate(i, k[0], k[1]);
      if (!(cp.depth > T(0))) continue;
      F += cp.force;
      Ma += (cp.point - k[0].r).cross(cp.force);
    }
    on[0] = {F, Ma};
    on[1] = {Vec3<T>(-F), Vec3<T>(-(Ma + (k[0].r - k[1].r).cross(F)))};
  }

  /// Per point δ, f_n, f_t, v_s, p and their rates (δ̇; the others' rates
  /// appear in no equation).
  template <class T>
  [[nodiscard]] auto internal_values(const T&, const state_of<T> auto&, const frame_kinematics<T>* k) const {
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return std::tuple_cat([&](int i) {
        const auto cp = evaluate(i, k[0], k[1]);
        return std::tuple{std::pair{cp.depth, cp.depth_rate}, std::pair{cp.fn, T(0)}, std::pair{cp.ft, T(0)},
                          std::pair{cp.vs, T(0)}, std::pair{cp.point, Vec3<T>(Vec3<T>::Zero())}};
      }(int(I))...);
    }(std::make_index_sequence<M>{});
  }

  /// The stored elastic energy Σ (2/5)·f_H·δ, for recover()'s energy.
  template <class T>
  [[nodiscard]] T potential_energy(const T&, const state_of<T> auto&, const frame_kinematics<T>* k) const {
    T e(0);
    for (int i = 0; i < M; ++i) {
      const auto cp = evaluate(i, k[0], k[1]);
      e += T(0.4) * cp.hertz * cp.depth;
    }
    return e;
  }

  /// The residual: each quantity of the contact as a function of the two
  /// frames' poses and rates (printed contact_F_a(r_a, R_a, …) and so on).
  [[nodiscard]] auto equations() const {
    using namespace expr;
    auto of = [&](auto f) {
      return call<decltype(f)::sh>(f, r_<0>, R_<0>, der(r_<0>), der(R_<0>), r_<1>, R_<1>, der(r_<1>), der(R_<1>));
    };
    auto point = [&]<int I>(std::integral_constant<int, I>) {
      constexpr int o = per_point * I;
      return boost::hana::make_tuple(
          eq(internal_<2, o + 0, var_kind::scalar>, of(quantity<o + 0>{this})),
          eq(internal_<2, o + 1, var_kind::scalar>, of(quantity<o + 1>{this})),
          eq(internal_<2, o + 2, var_kind::scalar>, of(quantity<o + 2>{this})),
          eq(internal_<2, o + 3, var_kind::scalar>, of(quantity<o + 3>{this})),
          eq(internal_<2, o + 4, var_kind::vec>, of(quantity<o + 4>{this})));
    };
    constexpr int f = per_point * M;
    auto flows = boost::hana::make_tuple(eq(F_<0>, of(quantity<f + 0>{this})), eq(M_<0>, of(quantity<f + 1>{this})),
                                         eq(F_<1>, of(quantity<f + 2>{this})), eq(M_<1>, of(quantity<f + 3>{this})));
    return [&]<int... I>(std::integer_sequence<int, I...>) {
      return boost::hana::flatten(boost::hana::make_tuple(point(std::integral_constant<int, I>{})..., flows));
    }(std::make_integer_sequence<int, M>{});
  }

 private:
  /// Quantity Q of the contact from the frames' poses and their rates: per
  /// point δ, f_n, f_t, v_s, p, then the flows F_a, M_a, F_b, M_b (frame
  /// coordinates; the flows are the negative of what the element exerts).
  template <int Q>
  struct quantity {
    static constexpr int flow = Q - per_point * M;  ///< < 0: a point's quantity
    static constexpr int point = Q / per_point, what = Q % per_point;
    static constexpr expr::shape sh =
        flow < 0 && what < 4 ? expr::shape::scalar : expr::shape::vec;
    static constexpr std::string_view name =
        flow < 0 ? detail::contact_quantity_names[what] : detail::contact_flow_names[flow];
    const Contact* c;
    template <class V, class Mt>
    auto operator()(const V& ra, const Mt& Ra, const V& va, const Mt& Rda, const V& rb, const Mt& Rb, const V& vb,
                    const Mt& Rdb) const {
      using T = typename V::Scalar;
      auto frame = [](const V& r, const Mt& R, const V& v, const Mt& Rd) {
        frame_kinematics<T> k;
        k.r = r;
        k.R = R;
        k.v = v;
        const Mt W = R * Rd.transpose();  // ω̃ in frame coordinates
        k.w = Vec3<T>(W(2, 1), W(0, 2), W(1, 0));
        return k;
      };
      const frame_kinematics<T> k[2] = {frame(ra, Ra, va, Rda), frame(rb, Rb, vb, Rdb)};
      if constexpr (flow < 0) {
        const auto cp = c->evaluate(point, k[0], k[1]);
        if constexpr (what == 0) return cp.depth;
        else if constexpr (what == 1) return cp.fn;
        else if constexpr (what == 2) return cp.ft;
        else if constexpr (what == 3) return cp.vs;
        else return cp.point;
      } else {
        wrench<T> on[2];
        c->wrenches(T(0), joint_state<T>{}, k, on);
        if constexpr (flow == 0) return Vec3<T>(-(Ra * on[0].f));
        else if constexpr (flow == 1) return Vec3<T>(-(Ra * on[0].n));
        else if constexpr (flow == 2) return Vec3<T>(-(Rb * on[1].f));
        else return Vec3<T>(-(Rb * on[1].n));
      }
    }
  };

  /// The law's scalars at point i of an overlap δ > 0: the Hertz force
  /// f_H = (4/3)·k·δ·√(R·k·δ), the normal force f_n = f_H·(1 + (3/2)·c·δ̇),
  /// never pulling, the slip speed v_s and g = f_t/v_s, the factor of the
  /// slip velocity in the friction force. The force on frame_a's side is
  /// f_n·N + g·v_t; each caller forms it in its own coordinates.
  template <class T>
  struct law_values {
    T hertz, fn, vs, g;
  };
  template <class T>
  [[nodiscard]] FLANGE_INLINE law_values<T> law(int i, const T& depth, const T& depth_rate, const T& vs2) const {
    using std::sqrt;
    law_values<T> l{};
    l.hertz = T(4.0 / 3.0 * k_) * depth * sqrt(T(reff_[i] * k_) * depth);
    const T f = l.hertz * (T(1) + T(1.5 * c_) * depth_rate);
    l.fn = f > T(0) ? f : T(0);
    if (vs2 > T(0)) {
      // Without a division by v_s below v_t (the ramp is v_s/v_t there), and
      // above it with v_s's square root taken beside μ's division.
      l.vs = sqrt(vs2);
      const T r2 = vs2 * T(inv_vt_ * inv_vt_);
      const T mu = T(mu_d_) + T(2 * (mu_s_ - mu_d_)) / (T(1) + r2);
      const T per_vs = r2 < T(1) ? mu * T(inv_vt_) : mu / l.vs;  // ramp·μ(v_s)/v_s
      l.g = l.fn * (per_vs + T(mu_v_));
    }
    return l;
  }

  void check_material(const char* which, const contact_material& m) const {
    const std::pair<const char*, double> fields[] = {{"stiffness", m.stiffness},
                                                     {"dissipation", m.dissipation},
                                                     {"static_friction", m.static_friction},
                                                     {"dynamic_friction", m.dynamic_friction},
                                                     {"viscous_friction", m.viscous_friction}};
    for (const auto& [what, x] : fields) {
      if (!std::isfinite(x) || x < 0)
        throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": ", which, ".", what, " = ", x,
                                             " must be finite and not negative"));
    }
    if (!(m.stiffness > 0))
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": ", which,
                                           ".stiffness = 0; a contact surface needs a stiffness"));
  }

  pair_type geometry_{};
  std::array<double, M> reff_{};
  /// Against a half-space: each point's sphere centre in frame_a, computed once.
  std::array<Vec3d, std::is_same_v<ShapeB, contact_shape::half_space> ? M : 0> center_{};
  double s_ = 0.5, k_ = 0, c_ = 0, mu_s_ = 0, mu_d_ = 0, mu_v_ = 0, inv_vt_ = 0;
};

}  // namespace flange
