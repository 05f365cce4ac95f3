// A user's own joint type: a hinge about frame_a's z axis, written against
// the joint concept (core/joint.hpp, docs/architecture.md "Write your own
// joint"). The ok half has every member it must have and simulates (it is
// plain: read_state and its state {.q, .v} are the concept's defaults, as
// are normalize, relative_pose and, from motion_base, pd and the biases); the ko
// half misses qdot, or with FLANGE_KO_PROJECT its motion's project
// (joint_motion_lacks_member.cpp), and is refused at the scene, naming the
// joint and the member.
#include <flange/equations_of_motion.hpp>
using namespace flange;

struct Hinge {
  static constexpr fixed_string name = "hinge";
  static constexpr std::string_view type_name = "Hinge";
  static constexpr role kind = role::joint;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 1> internals{{{"φ", expr::var_kind::scalar}}};
  static constexpr int nq = 1, nv = 1;
  static constexpr bool reversible = false;
  static constexpr int planar_normal() { return 2; }
  static constexpr bool moves_in_plane(int k) { return k == 2; }

  // Its equations: R₂ = R_z(φ)·R₁, r₂ = r₁, and no torque about z.
  auto equations() const {
    using namespace expr;
    const auto phi = internal_<2, 0, var_kind::scalar>;
    const param<Vec3d> n{Vec3d::UnitZ(), "e_z"};
    auto Rz = n * transpose(n) + (identity{} - n * transpose(n)) * cos(phi) - tilde(n) * sin(phi);
    return boost::hana::make_tuple(eq(r_<1>, r_<0>), orientation_eq(R_<1>, Rz * R_<0>), eq(F_<1>, -(Rz * F_<0>)),
                                   eq(M_<1>, -(Rz * M_<0>)), eq(zero<shape::scalar>{}, dot(M_<1>, n)));
  }
  // Its motion: a rotation about z, ω = φ̇·e_z, torque projected on z.
  template <class T>
  struct motion_t : motion_base<T> {
    coordinate_rotation<T, 2> E;
    zero_vec<T> p{};
    template <class V>
    auto w(const V& v) const {
      if constexpr (is_no_rates<V>) return zero_vec<T>{};
      else return axial<T, 2>(v[0]);
    }
#if !(defined(FLANGE_KO) && defined(FLANGE_KO_PROJECT))
    template <class N, class F>
    std::array<T, 1> project(const N& n, const F&) const { return {n.template get<2>()}; }
#endif
    template <int>
    motion_pair<axial_vec<T, 2>, zero_vec<T>> col() const { return {axial<T, 2>(T(1)), {}}; }
  };
  template <class T, int, bool>
  motion_t<T> motion(const T* q) const {
    using std::cos, std::sin;
    motion_t<T> m;
    m.E = {cos(q[0]), sin(q[0])};
    return m;
  }
#if !defined(FLANGE_KO) || defined(FLANGE_KO_PROJECT)
  template <class T>
  void qdot(const T*, const T* v, T* qd) const { qd[0] = v[0]; }
#endif
  static std::array<double, 1> neutral() { return {0.0}; }
  template <class T, class Set>
  void write_internals(const T* q, const T* v, Set&& set) const { set(0, q[0], v[0]); }
};

int main() {
  auto s = scene(World<"world">{}, Hinge{}, FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"b">({.m = 1.0}),
                 connect<"world.frame_b", "hinge.frame_a">, connect<"hinge.frame_b", "rod.frame_a">,
                 connect<"rod.frame_b", "b.frame_a">);
  auto x = initial_state<"hinge">(s, {.q = 0.3});
  decltype(x) dx;
  s(x, dx, 0.0);
  return dx[1] < 0 ? 0 : 1;
}
