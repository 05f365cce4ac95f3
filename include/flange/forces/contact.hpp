// Contact: compliant contact between two shapes, one attached at each frame,
// with Hunt–Crossley's normal force and Coulomb friction on a Stribeck
// curve, in the form of Simbody's HuntCrossleyForce.
//
//   Contact<"foot_ground", contact_shape::sphere, contact_shape::half_space>(
//       {.a = {.radius = 0.02}, .b = {.n = {0, 1, 0}},
//        .material_a = {.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7},
//        .material_b = {.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.9, .dynamic_friction = 0.7}})
//
// Shape a sits at frame_a (a sphere centred on its origin), shape b at frame_b
// (a sphere, or a half-space {p : n·p ≤ offset} in frame_b's coordinates, n
// its outward unit normal; a half-space on the World is a ground or a wall).
// Pairs: sphere–half-space, sphere–sphere. Which shapes can touch is written
// in the scene, one Contact per pair; shapes that no Contact pairs pass
// through each other.
//
// With δ the penetration (the overlap of the shapes along N, the normal from
// b toward a), δ̇ its rate, R the effective radius (a sphere's radius against
// a half-space, r_a·r_b/(r_a + r_b) between spheres), and the materials
// combined as Simbody combines them (k_i = E_i^(2/3), s = k_a/(k_a + k_b),
// k = k_b·s, c = c_b·s + c_a·(1 − s), μ = 2·μ_a·μ_b/(μ_a + μ_b)):
//
//   f_H = (4/3)·k·δ·√(R·k·δ)           Hertz (= (4/3)·E·√R·δ^(3/2), E = k^(3/2))
//   f_n = max(0, f_H·(1 + (3/2)·c·δ̇))  Hunt–Crossley: pushes, never pulls
//   f_t = f_n·(min(v_s/v_t, 1)·(μ_d + 2·(μ_s − μ_d)/(1 + (v_s/v_t)²)) + μ_v·v_s)
//
// f_t opposes the slip velocity v_s of a on b at the contact point, which
// lies at the middle of the overlap, moved by δ·(1/2 − s) along N (toward
// the softer surface). The stored energy is (2/5)·f_H·δ. Unlike Simbody, the
// friction is f_n's (never pushing when the normal force would pull).
//
// f_n grows like δ^(3/2) from first touch, so the force is C¹ in the state;
// the friction's slope jumps at v_s = v_t. A scene without a Contact has none
// of this arithmetic. The element's internal variables are δ, f_n, f_t and
// v_s (recover(…)["foot_ground.δ"], …).
#pragma once
#include <algorithm>
#include <cmath>
#include <type_traits>

#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"

namespace flange {

/// The shapes a Contact pairs.
namespace contact_shape {
/// A sphere centred on its frame's origin; radius 0 is a point.
struct sphere {
  double radius = 0;  ///< [m]
};
/// The half-space {p : n·p ≤ offset}, p in its frame's coordinates.
struct half_space {
  Vec3d n = Vec3d::UnitZ();  ///< outward unit normal
  double offset = 0;         ///< [m]
};
}  // namespace contact_shape

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
                "flange: Contact pairs a sphere (frame_a) with a half-space or a sphere (frame_b); this pair of "
                "shapes (the template arguments) is not supported");
};
}  // namespace diagnostic

namespace detail {
/// A contact's numbers at one instant (world coordinates).
template <class T>
struct contact_point {
  T depth{0}, depth_rate{0}, fn{0}, ft{0}, vs{0}, hertz{0};
  Vec3<T> point = Vec3<T>::Zero();  ///< where the force acts
  Vec3<T> force = Vec3<T>::Zero();  ///< on frame_a's side; frame_b's side takes −force
};
}  // namespace detail

template <fixed_string Name, class ShapeA, class ShapeB>
class Contact {
  static constexpr bool against_half_space =
      std::is_same_v<ShapeA, contact_shape::sphere> && std::is_same_v<ShapeB, contact_shape::half_space>;
  static constexpr bool between_spheres =
      std::is_same_v<ShapeA, contact_shape::sphere> && std::is_same_v<ShapeB, contact_shape::sphere>;

 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "Contact";
  static constexpr role kind = role::force;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 4> internals{{{"δ", expr::var_kind::scalar},
                                                           {"f_n", expr::var_kind::scalar},
                                                           {"f_t", expr::var_kind::scalar},
                                                           {"v_s", expr::var_kind::scalar}}};
  /// Needs the frames' positions and velocities (a position pass in the dynamics).
  static constexpr bool needs_motion = true;
  static constexpr bool line_of_action = false;
  /// A force at the contact point: a force and a torque about each frame's origin.
  static constexpr bool exerts_force = true, exerts_torque = true;

  struct params {
    ShapeA a{};                           ///< the shape at frame_a
    ShapeB b{};                           ///< the shape at frame_b
    contact_material material_a{};        ///< shape a's surface
    contact_material material_b{};        ///< shape b's surface
    double transition_velocity = 1e-3;    ///< v_t [m/s]: static friction peaks at this slip speed
  };

  explicit Contact(params p) : shape_a_(p.a), shape_b_(p.b) {
    if constexpr (against_half_space || between_spheres) {
      check_sphere("a", shape_a_);
      if constexpr (between_spheres) {
        check_sphere("b", shape_b_);
        reff_ = shape_a_.radius * shape_b_.radius / (shape_a_.radius + shape_b_.radius);
      } else {
        detail::require_finite(name.view(), type_name, "b.offset", shape_b_.offset);
        detail::require_finite(name.view(), type_name, "b.n", shape_b_.n);
        if (!(std::abs(shape_b_.n.norm() - 1) <= 1e-9))
          throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": the half-space's normal b.n = [",
                                               shape_b_.n.transpose(), "] is not a unit vector (norm ",
                                               shape_b_.n.norm(), ")"));
        reff_ = shape_a_.radius;
      }
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

  /// The contact at the two frames' motion (frame_kinematics: R turns world
  /// into the frame, w in frame coordinates).
  template <class T>
  [[nodiscard]] detail::contact_point<T> evaluate(const frame_kinematics<T>& a, const frame_kinematics<T>& b) const {
    using std::sqrt;
    detail::contact_point<T> cp;
    // N, from b toward a, and the distance from b's surface to a's centre along N.
    Vec3<T> N;
    T gap;
    Vec3<T> surface;  // the point of b's surface under a's centre
    if constexpr (between_spheres) {
      const Vec3<T> d = a.r - b.r;
      const T dist = sqrt(d.squaredNorm());
      if (!(dist > T(0))) return cp;  // concentric: no direction (Simbody likewise applies nothing)
      N = d / dist;
      gap = dist - T(shape_b_.radius);
      surface = b.r + T(shape_b_.radius) * N;
    } else {
      N = b.R.transpose() * shape_b_.n.template cast<T>();
      gap = N.dot(a.r - b.r) - T(shape_b_.offset);
      surface = a.r - gap * N;
    }
    cp.depth = T(shape_a_.radius) - gap;
    if (!(cp.depth > T(0))) {
      cp.depth = T(0);
      return cp;
    }
    // The middle of the overlap, moved toward the softer side.
    cp.point = surface - (T(0.5) * cp.depth) * N + (cp.depth * T(0.5 - s_)) * N;
    // The velocity of b relative to a at that point: δ̇ along N, the slip across it.
    const Vec3<T> va = a.v + (a.R.transpose() * a.w).cross(cp.point - a.r);
    const Vec3<T> vb = b.v + (b.R.transpose() * b.w).cross(cp.point - b.r);
    const Vec3<T> v = vb - va;
    cp.depth_rate = v.dot(N);
    const Vec3<T> vt = v - cp.depth_rate * N;
    cp.hertz = T(4.0 / 3.0 * k_) * cp.depth * sqrt(T(reff_ * k_) * cp.depth);
    const T f = cp.hertz * (T(1) + T(1.5 * c_) * cp.depth_rate);
    cp.fn = f > T(0) ? f : T(0);
    cp.force = cp.fn * N;
    const T vs2 = vt.squaredNorm();
    if (vs2 > T(0)) {
      cp.vs = sqrt(vs2);
      const T r = cp.vs * T(inv_vt_);
      const T ramp = r < T(1) ? r : T(1);
      cp.ft = cp.fn * (ramp * (T(mu_d_) + T(2 * (mu_s_ - mu_d_)) / (T(1) + r * r)) + T(mu_v_) * cp.vs);
      cp.force += (cp.ft / cp.vs) * vt;
    }
    return cp;
  }

  /// What the element exerts on the rest of the scene at each of its frames:
  /// force and torque (about the frame's origin), world coordinates.
  template <class T>
  void wrenches(const T&, const state_of<T> auto&, const frame_kinematics<T>* k, wrench<T>* on) const {
    const auto cp = evaluate(k[0], k[1]);
    on[0] = {cp.force, (cp.point - k[0].r).cross(cp.force)};
    on[1] = {-cp.force, (cp.point - k[1].r).cross(-cp.force)};
  }

  /// δ, f_n, f_t, v_s and their rates (δ̇; the forces' rates appear in no equation).
  template <class T>
  [[nodiscard]] std::array<std::pair<T, T>, 4> internal_values(const T&, const state_of<T> auto&,
                                                               const frame_kinematics<T>* k) const {
    const auto cp = evaluate(k[0], k[1]);
    return {std::pair{cp.depth, cp.depth_rate}, std::pair{cp.fn, T(0)}, std::pair{cp.ft, T(0)},
            std::pair{cp.vs, T(0)}};
  }

  /// The stored elastic energy (2/5)·f_H·δ, for recover()'s energy.
  template <class T>
  [[nodiscard]] T potential_energy(const T&, const state_of<T> auto&, const frame_kinematics<T>* k) const {
    const auto cp = evaluate(k[0], k[1]);
    return T(0.4) * cp.hertz * cp.depth;
  }

  static constexpr auto depth = internal_<2, 0, expr::var_kind::scalar>;
  static constexpr auto f_n = internal_<2, 1, expr::var_kind::scalar>;
  static constexpr auto f_t = internal_<2, 2, expr::var_kind::scalar>;
  static constexpr auto v_s = internal_<2, 3, expr::var_kind::scalar>;

  /// The residual: each quantity of the contact as a function of the two
  /// frames' poses and rates (printed contact_F_a(r_a, R_a, …) and so on).
  [[nodiscard]] auto equations() const {
    using namespace expr;
    auto of = [&](auto f) {
      return call<decltype(f)::sh>(f, r_<0>, R_<0>, der(r_<0>), der(R_<0>), r_<1>, R_<1>, der(r_<1>), der(R_<1>));
    };
    return boost::hana::make_tuple(eq(depth, of(quantity<0>{this})), eq(f_n, of(quantity<1>{this})),
                                   eq(f_t, of(quantity<2>{this})), eq(v_s, of(quantity<3>{this})),
                                   eq(F_<0>, of(quantity<4>{this})), eq(M_<0>, of(quantity<5>{this})),
                                   eq(F_<1>, of(quantity<6>{this})), eq(M_<1>, of(quantity<7>{this})));
  }

 private:
  /// Quantity Q of the contact from the frames' poses and their rates: δ,
  /// f_n, f_t, v_s, then the flows F_a, M_a, F_b, M_b (frame coordinates;
  /// the flows are the negative of what the element exerts).
  template <int Q>
  struct quantity {
    static constexpr expr::shape sh = Q < 4 ? expr::shape::scalar : expr::shape::vec;
    static constexpr const char* name = Q == 0 ? "contact_depth" : Q == 1 ? "contact_f_n" : Q == 2 ? "contact_f_t"
                                        : Q == 3 ? "contact_v_s" : Q == 4 ? "contact_F_a" : Q == 5 ? "contact_M_a"
                                        : Q == 6 ? "contact_F_b" : "contact_M_b";
    const Contact* c;
    template <class V, class M>
    auto operator()(const V& ra, const M& Ra, const V& va, const M& Rda, const V& rb, const M& Rb, const V& vb,
                    const M& Rdb) const {
      using T = typename V::Scalar;
      auto frame = [](const V& r, const M& R, const V& v, const M& Rd) {
        frame_kinematics<T> k;
        k.r = r;
        k.R = R;
        k.v = v;
        const M W = R * Rd.transpose();  // ω̃ in frame coordinates
        k.w = Vec3<T>(W(2, 1), W(0, 2), W(1, 0));
        return k;
      };
      const frame_kinematics<T> a = frame(ra, Ra, va, Rda), b = frame(rb, Rb, vb, Rdb);
      const auto cp = c->evaluate(a, b);
      if constexpr (Q == 0) return cp.depth;
      else if constexpr (Q == 1) return cp.fn;
      else if constexpr (Q == 2) return cp.ft;
      else if constexpr (Q == 3) return cp.vs;
      else if constexpr (Q == 4) return Vec3<T>(-(Ra * cp.force));
      else if constexpr (Q == 5) return Vec3<T>(-(Ra * (cp.point - ra).cross(cp.force)));
      else if constexpr (Q == 6) return Vec3<T>(Rb * cp.force);
      else return Vec3<T>(Rb * (cp.point - rb).cross(cp.force));
    }
  };

  void check_sphere(const char* which, const contact_shape::sphere& s) const {
    detail::require_finite(name.view(), type_name, which[0] == 'a' ? "a.radius" : "b.radius", s.radius);
    if (s.radius < 0)
      throw parameter_error(detail::concat(type_name, " \"", name.view(), "\": sphere ", which, ".radius = ",
                                           s.radius, " is negative"));
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

  ShapeA shape_a_;
  ShapeB shape_b_;
  double reff_ = 0, s_ = 0.5, k_ = 0, c_ = 0, mu_s_ = 0, mu_d_ = 0, mu_v_ = 0, inv_vt_ = 0;
};

}  // namespace flange
