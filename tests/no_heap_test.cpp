// No heap allocation in the derivative, the residual, or the stepping loop.
// Two independent guards: Eigen's EIGEN_RUNTIME_NO_MALLOC assertion, and a
// replaced global operator new that counts every allocation in the process.
#define EIGEN_RUNTIME_NO_MALLOC
#include <atomic>
#include <cstdlib>
#include <new>

#include <catch2/catch.hpp>
#include <flange/dynamics/articulated_body.hpp>
#include <flange/forces/line_force.hpp>
#include <flange/forces/world_force.hpp>
#include <flange/simulate/odeint.hpp>

#include "random_params.hpp"

namespace {
std::atomic<long> allocations{0};
}
void* operator new(std::size_t n) {
  ++allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace flange;

namespace {
/// Runs f with Eigen's heap forbidden and returns how many allocations it made.
template <class F>
long count_allocations(F&& f) {
  const long before = allocations;
  Eigen::internal::set_is_malloc_allowed(false);
  f();
  Eigen::internal::set_is_malloc_allowed(true);
  return allocations - before;
}
}  // namespace

TEST_CASE("the derivative allocates nothing") {
  std::mt19937 rng(5);
  const auto arm = models::robot_arm({}, [](double t) { return Vec3d(0, 0, std::sin(t)); });
  const auto chain = models::chain<6, models::runtime_axes>(test::chain_params<6>(rng));
  std::array<double, 2> x{0.1, 0.2}, dx;
  std::array<double, 12> y{}, dy;
  eigen_state<decltype(arm)> xe(0.1, 0.2), dxe;
  // Line forces and world loads take the position pass; friction a tanh.
  const auto sprung = scene(World<"world">{}, Revolute<"joint", axis::z, axis_law::friction>({.d = 0.1, .f_c = 0.2}),
                            FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1.0}),
                            SpringDamper<"spring">({.c = 20, .s0 = 0.1, .d = 0.3}),
                            WorldForce<"push">({.value = Vec3d(1, 0, 0)}), connect<"world.frame_b", "joint.frame_a">,
                            connect<"joint.frame_b", "rod.frame_a">, connect<"rod.frame_b", "mass.frame_a">,
                            connect<"world.frame_b", "spring.frame_a">, connect<"rod.frame_b", "spring.frame_b">,
                            connect<"rod.frame_b", "push.frame_b">);
  std::array<double, 2> z{0.3, 0.4}, dz;
  CHECK(count_allocations([&] {
          for (int i = 0; i < 100; ++i) {
            sprung(z, dz, 0.0);
            arm(x, dx, 0.1 * i);
            arm(xe, dxe, 0.1 * i);
            chain(y, dy, 0.0);
            accelerations_articulated_body(chain, 0.0, y.data(), y.data() + 6, dy.data() + 6);
          }
        }) == 0);
}

TEST_CASE("the residual allocates nothing") {
  const auto arm = models::robot_arm();
  const auto sol = recover(arm, 0.0, std::array<double, 2>{0.3, 0.1});
  double sum = 0;
  CHECK(count_allocations([&] { sum += residual(arm, 0.0, sol.y, sol.yd).sum(); }) == 0);
  CHECK(std::isfinite(sum));
}

TEST_CASE("stepping loops allocate nothing once the stepper exists") {
  const auto crane = models::gantry_crane({}, [](double t) { return std::sin(t); });
  using X = decltype(crane)::state_type;
  using E = eigen_state<decltype(crane)>;
  X x{0, -0.5, 0, 0};
  odeint::runge_kutta4<X> rk4;
  auto dopri = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>());
  odeint::runge_kutta4<E, double, E, double, odeint::vector_space_algebra> rk4e;
  E xe(0, -0.5, 0, 0);
  // Steppers size their buffers on first use (odeint's resizer): do one step first.
  rk4.do_step(crane, x, 0.0, 1e-3);
  rk4e.do_step(crane, xe, 0.0, 1e-3);
  double t = 0, dt = 1e-3;
  dopri.try_step(crane, x, t, dt);
  CHECK(count_allocations([&] {
          for (int i = 0; i < 1000; ++i) {
            rk4.do_step(crane, x, 0.0, 1e-3);
            rk4e.do_step(crane, xe, 0.0, 1e-3);
          }
          for (int i = 0; i < 1000; ++i) dopri.try_step(crane, x, t, dt);
        }) == 0);
}

TEST_CASE("the allocation counter sees allocations") {
  // The guard can fail: an allocation inside it is counted.
  // (Through a volatile pointer: a bare new/delete pair may be elided.)
  CHECK(count_allocations([] {
          int* volatile p = new int(1);
          delete p;
        }) == 1);
}
