// energy() (dynamics/energy.hpp): a scene's energy from positions and
// velocities alone. Checked against a pendulum's closed form (kinetic,
// gravity's and a joint spring's potential), against recover() at random
// states of a branched scene, and through the mass matrix read off its
// kinetic energy by dual numbers (energy_mass_matrix) against the
// composite-rigid-body pass, which shares no code with it.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <flange/dynamics/energy_mass_matrix.hpp>
#include <flange/equations_of_motion.hpp>

using namespace flange;

TEST_CASE("energy() of a pendulum with a joint spring: ½(m·l² + J_zz)·ω², m·g·l·sin φ and ½·c·(φ − φ₀)²") {
  const double m = 1.7, l = 0.6, Jzz = 0.09, c = 12.0, phi0 = 0.3;
  const auto s = scene(World<"world">{}, Revolute<"pivot", axis::z, axis_law::spring_damper>({.c = c, .d = 0.5, .phi0 = phi0}),
                       FixedTranslation<"rod">({.d = {l, 0, 0}}),
                       Body<"bob">({.m = m, .J = Vec3d(0.05, 0.06, Jzz).asDiagonal()}),
                       connect<"world.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rod.frame_a">,
                       connect<"rod.frame_b", "bob.frame_a">);
  for (double phi : {-2.0, 0.0, 0.4, 2.9})
    for (double w : {-3.0, 0.0, 1.5}) {
      const std::array<double, 2> x{phi, w};
      const auto e = energy(s, 0.0, x);
      CHECK(e.kinetic == Approx(0.5 * (m * l * l + Jzz) * w * w).margin(1e-15));
      CHECK(e.gravity_potential == Approx(m * 9.81 * l * std::sin(phi)).margin(1e-14));
      CHECK(e.elastic_potential == Approx(0.5 * c * (phi - phi0) * (phi - phi0)).margin(1e-15));
    }
}

namespace {
/// A branched scene of several joint kinds: a revolute on a run-time axis
/// carrying an offset body and, beyond it, a ball joint and a slider; a
/// second branch on a universal joint with a line spring between the two
/// branches' bodies.
auto branched() {
  return scene(World<"world">{}, Revolute<"hip">({.n = Vec3d(0.2, 0.3, 1.0).normalized()}),
               FixedTranslation<"thigh">({.d = {0.5, 0.1, -0.05}}),
               Body<"b1", cm::offset>({.m = 2.0, .J = Vec3d(0.03, 0.04, 0.05).asDiagonal(), .r_cm = {0.1, 0.02, 0}}),
               Spherical<"knee">{}, FixedTranslation<"shin">({.d = {0.0, -0.4, 0.1}}),
               Body<"b2">({.m = 1.2, .J = Vec3d(0.02, 0.01, 0.02).asDiagonal()}), Prismatic<"foot", axis::y>({}),
               Body<"b3", cm::offset>({.m = 0.4, .J = Vec3d(0.004, 0.003, 0.002).asDiagonal(), .r_cm = {0, 0, 0.05}}),
               Universal<"shoulder">{}, FixedTranslation<"arm">({.d = {-0.3, 0.2, 0.1}}),
               Body<"b4">({.m = 0.8, .J = Vec3d(0.01, 0.012, 0.008).asDiagonal()}),
               SpringDamper<"spring">({.c = 40, .s0 = 0.3, .d = 0.2}),
               connect<"world.frame_b", "hip.frame_a">, connect<"world.frame_b", "shoulder.frame_a">,
               connect<"hip.frame_b", "thigh.frame_a">, connect<"thigh.frame_b", "b1.frame_a">,
               connect<"thigh.frame_b", "knee.frame_a">, connect<"knee.frame_b", "shin.frame_a">,
               connect<"shin.frame_b", "b2.frame_a">, connect<"shin.frame_b", "foot.frame_a">,
               connect<"shin.frame_b", "spring.frame_a">, connect<"foot.frame_b", "b3.frame_a">,
               connect<"shoulder.frame_b", "arm.frame_a">, connect<"arm.frame_b", "b4.frame_a">,
               connect<"arm.frame_b", "spring.frame_b">);
}
}  // namespace

TEST_CASE("energy() equals recover()'s energies, and its mass matrix (by dual numbers) the composite-rigid-body M") {
  const auto s = branched();
  using S = decltype(s);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  double worst_M = 0;
  for (int k = 0; k < 10; ++k) {
    typename S::state_type x;
    for (auto& xi : x) xi = u(rng);
    normalize(s, x);
    const auto e = energy(s, 0.3, x);
    const auto sol = recover(s, 0.3, x);
    // The same functions fill both (energy.hpp), so equal to the last bit:
    // this checks that energy() splits the state as recover() does.
    CHECK(e.kinetic == sol.kinetic);
    CHECK(e.gravity_potential == sol.gravity_potential);
    CHECK(e.elastic_potential == sol.elastic_potential);
    CHECK(e.elastic_potential > 0);  // the line spring is there
    // T = ½·vᵀ·M·v with M from the composite-rigid-body pass.
    const auto M = mass_matrix(s, x.data());
    const Eigen::Map<const Eigen::Matrix<double, S::n_v, 1>> v(x.data() + S::n_q);
    CHECK(e.kinetic == Approx(0.5 * v.dot(M * v)).epsilon(1e-13));
    // M read off the kinetic energy by dual numbers, against the pass.
    const auto Me = energy_mass_matrix(s, x);
    worst_M = std::max(worst_M, (Me - M).cwiseAbs().maxCoeff() / M.cwiseAbs().maxCoeff());
  }
  INFO("largest relative difference of the two mass matrices " << worst_M);
  CHECK(worst_M <= 1e-14);
}
