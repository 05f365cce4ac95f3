// Every joint kind against its own laws, over random states, both ways round.
// A joint states its kinematics several times: as its motion (E, p, S and
// the biases the algorithms use), its relative pose (cut forces, output),
// its internals (the DAE's variables) and, where it can close a loop, its
// cut state. These must be one kinematics:
//   * a relative_pose(q) the joint states is the motion<+1>(q) densified
//     (flange's joints state none and take that default; RevoluteOwnPose
//     below states one, as a user's joint may), and motion<−1>(q) is its
//     inverse (E⁻ = E⁺ᵀ, p⁻ = −E⁺·p⁺);
//   * the motion subspace is the derivative of the pose along q̇ = qdot(q, v):
//     ω = m.w(v) from Ṙ = −ω̃·R, ṗ = m.pd(v), against central differences
//     and against dual numbers;
//   * the biases are the rates of S·v at constant v, against central differences;
//   * m.project is Sᵀ and m.col<k>() is S's column k;
//   * read_state after write_internals gives back (q, v);
//   * cut_state of the pose and its rates gives back (q, v), where the joint
//     can be cut;
//   * a joint with fixed_subspace has the same columns at every q;
//   * normalize keeps a quaternion joint's q at unit norm and its rotation.
// The joints are models::every_joint_kind's list (models/tree.hpp draws
// random trees from it).
#include <catch2/catch.hpp>
#include <flange/equations_of_motion.hpp>
#include <flange/models/tree.hpp>

#include <random>

using namespace flange;

namespace {

using dual1 = dual<double, 1>;

template <class X>
Vec3d dense3(const X& x) {
  if constexpr (requires { x.dense(); }) {
    const auto d = x.dense();
    return Vec3d(double(d(0)), double(d(1)), double(d(2)));
  } else {
    return Vec3d(double(x(0)), double(x(1)), double(x(2)));
  }
}

template <class J, int Dir, class T = double>
auto motion_at(const J& j, const T* q) {
  return j.template motion<T, Dir, true>(q);
}

/// The joint's relative pose and rates as motion<Dir> has them, in double.
struct motion_values {
  Mat3d E;
  Vec3d p, w, pd, w_bias, pd_bias;
};
template <int Dir, class J>
motion_values values(const J& j, const double* q, const double* v) {
  const auto m = motion_at<J, Dir>(j, q);
  return {dense_rotation<double>(m.E), dense3(m.p), dense3(m.w(v)), dense3(m.pd(v)), dense3(m.w_bias(v)),
          dense3(m.pd_bias(v))};
}

/// ω from Ṙ for R rotating parent coordinates into child coordinates: Ṙ = −ω̃·R.
Vec3d omega_from(const Mat3d& R, const Mat3d& Rd) {
  const Mat3d W = -Rd * R.transpose();
  return Vec3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1)) / 2;
}

/// A random state of J: q from random numbers (a quaternion normalized; an
/// angle within (−π, π), so that a cut state's atan2 gives it back).
template <class J>
void random_state(const J& j, std::mt19937& rng, std::array<double, J::nq>& q, std::array<double, J::nv>& v) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& x : q) x = 3.0 * u(rng);
  for (auto& x : v) x = 2.0 * u(rng);
  normalize_joint(j, q.data());
}

/// q + h·q̇ (q̇ = qdot(q, v)).
template <class J>
std::array<double, J::nq> moved(const J& j, const std::array<double, J::nq>& q, const std::array<double, J::nv>& v,
                                double h) {
  std::array<double, J::nq> qd{}, r{};
  j.qdot(q.data(), v.data(), qd.data());
  for (int i = 0; i < J::nq; ++i) r[i] = q[i] + h * qd[i];
  return r;
}

/// Stores what write_internals sets and hands it to read_state.
struct internals_store {
  std::array<std::array<double, 9>, 8> value{}, rate{};
  template <class X>
  static void put(const X& x, std::array<double, 9>& to) {
    if constexpr (std::is_arithmetic_v<X>) to[0] = x;
    else
      for (int i = 0; i < int(x.size()); ++i) to[i] = x.data()[i];
  }
  auto setter() {
    return [this](int i, const auto& x, const auto& xd) {
      put(x, value[i]);
      put(xd, rate[i]);
    };
  }
  auto getter() const {
    return [this](int i, bool derivative) { return derivative ? rate[i].data() : value[i].data(); };
  }
};

/// A Revolute that states its own relative_pose (frame_b turned by +φ about
/// n), as a user's joint may: the laws hold it to the motion.
struct RevoluteOwnPose : Revolute<"own", axis::any> {
  using Revolute::Revolute;
  template <class T>
  pose<T> relative_pose(const T* q) const {
    return {axis_rotation<T>(n().cast<T>(), q[0]), Vec3<T>::Zero()};
  }
};

template <class J>
void check_laws(const J& j, std::uint32_t seed) {
  constexpr int nq = J::nq, nv = J::nv;
  std::mt19937 rng(seed);
  INFO(J::type_name << " \"" << J::name.view() << "\"");
  for (int trial = 0; trial < 20; ++trial) {
    std::array<double, nq> q;
    std::array<double, nv> v;
    random_state(j, rng, q, v);
    INFO("trial " << trial);

    // relative_pose is the motion; the reverse motion is its inverse.
    // (A joint without its own relative_pose takes the motion's, which
    // relative_pose_of densifies: flange's joints do; a user's may not.)
    const auto fwd = values<+1>(j, q.data(), v.data());
    const pose<double> x = relative_pose_of(j, q.data());
    if constexpr (requires { j.relative_pose(q.data()); }) {
      CHECK((x.R - fwd.E).norm() < 1e-14);
      CHECK((x.p - fwd.p).norm() < 1e-14);
    }
    CHECK((fwd.E * fwd.E.transpose() - Mat3d::Identity()).norm() < 1e-14);
    if constexpr (J::reversible) {
      const auto rev = values<-1>(j, q.data(), v.data());
      CHECK((rev.E - fwd.E.transpose()).norm() < 1e-14);
      CHECK((rev.p + fwd.E * fwd.p).norm() < 1e-14);
    }

    // S·v is the derivative of the pose along q̇, both ways round, and the
    // biases are the derivative of S·v at constant v (central differences,
    // step h: error O(h²) ≈ 1e-10 against rates of order 10).
    const double h = 1e-5;
    const auto qp = moved(j, q, v, h), qm = moved(j, q, v, -h);
    const auto check_rates = [&]<int Dir>(std::integral_constant<int, Dir>) {
      const auto m0 = values<Dir>(j, q.data(), v.data());
      const auto mp = values<Dir>(j, qp.data(), v.data());
      const auto mm = values<Dir>(j, qm.data(), v.data());
      const Mat3d Ed = (mp.E - mm.E) / (2 * h);
      CHECK((omega_from(m0.E, Ed) - m0.w).norm() < 1e-8);
      CHECK(((mp.p - mm.p) / (2 * h) - m0.pd).norm() < 1e-8);
      CHECK(((mp.w - mm.w) / (2 * h) - m0.w_bias).norm() < 1e-8);
      CHECK(((mp.pd - mm.pd) / (2 * h) - m0.pd_bias).norm() < 1e-8);

      // Sᵀ and the columns: project(n, f) = Sᵀ·(n, f) with S's columns
      // (w(e_k), E·pd(e_k)), and col<k>() the same columns.
      const auto m = motion_at<J, Dir>(j, q.data());
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const Vec3d n(u(rng), u(rng), u(rng)), f(u(rng), u(rng), u(rng));
      const auto g = m.project(to_svec(n), to_svec(f));
      detail::static_for<nv>([&](auto kc) {
        constexpr int k = decltype(kc)::value;
        std::array<double, nv> e{};
        e[k] = 1;
        const Vec3d s_ang = dense3(m.w(e.data())), s_lin = m0.E * dense3(m.pd(e.data()));
        const auto col = m.template col<k>();
        CHECK((dense3(col.ang) - s_ang).norm() < 1e-14);
        CHECK((dense3(col.lin) - s_lin).norm() < 1e-14);
        CHECK(std::abs(g[k] - (s_ang.dot(n) + s_lin.dot(f))) < 1e-14);
      });

      // Dual numbers: q + ε·q̇ carried through the motion gives Ė and ṗ exactly.
      std::array<double, nq> qd{};
      j.qdot(q.data(), v.data(), qd.data());
      std::array<dual1, nq> qe;
      for (int i = 0; i < nq; ++i) {
        qe[i] = dual1(q[i]);
        qe[i].d[0] = qd[i];
      }
      const auto me = motion_at<J, Dir, dual1>(j, qe.data());
      Mat3d E_dual, Ed_dual;
      for (int k = 0; k < 3; ++k) {
        const auto c = rot(me.E, to_svec(Vec3<dual1>(Vec3d::Unit(k).cast<dual1>()))).dense();
        for (int i = 0; i < 3; ++i) {
          E_dual(i, k) = c(i).v;
          Ed_dual(i, k) = c(i).d[0];
        }
      }
      const auto pe = me.p.dense();
      Vec3d pd_dual;
      for (int i = 0; i < 3; ++i) pd_dual(i) = pe(i).d[0];
      CHECK((omega_from(E_dual, Ed_dual) - m0.w).norm() < 1e-13);
      CHECK((pd_dual - m0.pd).norm() < 1e-13);
    };
    check_rates(std::integral_constant<int, +1>{});
    if constexpr (J::reversible) check_rates(std::integral_constant<int, -1>{});

    // read_state ∘ write_internals is the identity.
    internals_store store;
    j.write_internals(q.data(), v.data(), store.setter());
    std::array<double, nq> q2{};
    std::array<double, nv> v2{};
    read_joint_state(j, store.getter(), q2.data(), v2.data());
    const auto same_pose = [&](const std::array<double, nq>& a) {
      const pose<double> y = relative_pose_of(j, a.data());
      return (y.R - x.R).norm() < 1e-13 && (y.p - x.p).norm() < 1e-13;
    };
    CHECK(same_pose(q2));  // a quaternion may come back as −q: compare the pose
    for (int i = 0; i < nv; ++i) CHECK(std::abs(v2[i] - v[i]) < 1e-13);

    // cut_state ∘ relative_pose is the identity, where the joint can be cut:
    // the relative angular velocity in frame_a coordinates, ṗ in frame_a's.
    if constexpr (requires { J::as_cut; }) {
      std::array<double, nq> q3{};
      std::array<double, nv> v3{};
      j.cut_state(x.R, x.p, Vec3d(fwd.E.transpose() * fwd.w), fwd.pd, q3.data(), v3.data());
      CHECK(same_pose(q3));
      for (int i = 0; i < nv; ++i) CHECK(std::abs(v3[i] - v[i]) < 1e-12);
    }

    // A fixed subspace does not depend on q.
    if constexpr (requires { J::fixed_subspace; }) {
      if constexpr (J::fixed_subspace) {
        std::array<double, nq> qo;
        std::array<double, nv> vo;
        random_state(j, rng, qo, vo);
        const auto m1 = motion_at<J, +1>(j, q.data());
        const auto m2 = motion_at<J, +1>(j, qo.data());
        detail::static_for<nv>([&](auto kc) {
          constexpr int k = decltype(kc)::value;
          CHECK((dense3(m1.template col<k>().ang) - dense3(m2.template col<k>().ang)).norm() == 0);
          CHECK((dense3(m1.template col<k>().lin) - dense3(m2.template col<k>().lin)).norm() == 0);
        });
      }
    }

    // normalize: a quaternion scaled off unit norm comes back to it, with
    // the same pose.
    if constexpr (nq > nv) {
      std::array<double, nq> qs = q;
      for (int i = nq - 4; i < nq; ++i) qs[i] *= 1.3;
      normalize_joint(j, qs.data());
      double n2 = 0;
      for (int i = nq - 4; i < nq; ++i) n2 += qs[i] * qs[i];
      CHECK(std::abs(n2 - 1) < 1e-15);
      CHECK(same_pose(qs));
    }
  }
}

}  // namespace

TEST_CASE("every joint kind keeps its own laws: pose, motion, rates, internals, cut state, normalization") {
  const Vec3d n = Vec3d(0.3, -0.5, 0.8).normalized(), m = n.cross(Vec3d::UnitX()).normalized();
  std::uint32_t seed = 1;
  models::for_each_joint_kind([&](auto kind) {
    constexpr auto K = decltype(kind)::value;
    // Each kind with a typed axis (z, and x where the kind takes one) and a
    // run-time one.
    if constexpr (K == models::joint_kind::revolute) {
      check_laws(Revolute<"rz", axis::z>{}, seed++);
      check_laws(Revolute<"rx", axis::x>{}, seed++);
      check_laws(Revolute<"rn">({.n = n}), seed++);
      check_laws(RevoluteOwnPose({.n = n}), seed++);
    } else if constexpr (K == models::joint_kind::prismatic) {
      check_laws(Prismatic<"pz", axis::z>({}), seed++);
      check_laws(Prismatic<"pn">({.n = n}), seed++);
    } else if constexpr (K == models::joint_kind::spherical) {
      check_laws(Spherical<"ball">{}, seed++);
    } else if constexpr (K == models::joint_kind::universal) {
      check_laws(Universal<"uxy", axis::x, axis::y>{}, seed++);
      check_laws(Universal<"un">({.n_a = n, .n_b = m}), seed++);
    } else if constexpr (K == models::joint_kind::cylindrical) {
      check_laws(Cylindrical<"cz", axis::z>{}, seed++);
      check_laws(Cylindrical<"cn">({.n = n}), seed++);
    } else if constexpr (K == models::joint_kind::planar) {
      check_laws(Planar<"plz", axis::z, axis::x>{}, seed++);
      check_laws(Planar<"pln">({.n = n, .n_x = m}), seed++);
    } else if constexpr (K == models::joint_kind::free_motion) {
      check_laws(FreeMotion<"free">{}, seed++);
    } else {
      static_assert(K != K, "joint_laws_test: a joint kind of models::every_joint_kind has no case here; add one");
    }
  });
  CHECK(seed == 15);  // every joint above was checked
}
