// No heap allocation in the derivative, the residual, recovery, the Jacobian,
// the checked system, or any stepping loop once its stepper exists; and none
// per case in an ensemble.
//
// The counter (allocation_counter.cpp) sees every way to the heap; a test
// shows it sees an Eigen dynamic vector in Release. Scenes of 64 and more
// links are in large_scenes_test.cpp.
#include <cstdlib>
#include <new>

#include <catch2/catch.hpp>
#include <flange/dynamics/articulated_body.hpp>
#include <flange/ensemble/ensemble.hpp>
#include <flange/forces/contact.hpp>
#include <flange/forces/line_force.hpp>
#include <flange/forces/world_force.hpp>
#include <flange/simulate/checked.hpp>
#include <flange/models/chain.hpp>
#include <flange/simulate/jacobian.hpp>
#include <flange/simulate/odeint.hpp>
#include <flange/simulate/projected.hpp>
#include <flange/simulate/simulate.hpp>
#include <flange/joints/free_motion.hpp>
#include <flange/components/body.hpp>
#include <flange/models/linkages.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

#include "allocation_counter.hpp"
#include "random_params.hpp"

using namespace flange;

using test::count_allocations;

namespace {
/// A branched tree with every joint and force element (tests/tree_test.cpp).
constexpr auto tree_shape = models::random_tree_shape(3, 8, false);

auto sprung_arm() {
  // Line forces and world loads take the position pass; friction a tanh.
  return scene(World<"world">{}, Revolute<"joint", axis::z, axis_law::friction>({.d = 0.1, .f_c = 0.2}),
               FixedTranslation<"rod">({.d = {0.5, 0, 0}}), Body<"mass">({.m = 1.0}),
               SpringDamper<"spring">({.c = 20, .s0 = 0.1, .d = 0.3}), WorldForce<"push">({.value = Vec3d(1, 0, 0)}),
               connect<"world.frame_b", "joint.frame_a">, connect<"joint.frame_b", "rod.frame_a">,
               connect<"rod.frame_b", "mass.frame_a">, connect<"world.frame_b", "spring.frame_a">,
               connect<"rod.frame_b", "spring.frame_b">, connect<"rod.frame_b", "push.frame_b">);
}
}  // namespace

TEST_CASE("the allocation counter sees operator new, malloc and Eigen's dynamic vectors") {
  // The guard can fail. (Through volatile pointers: a bare pair may be elided.)
  CHECK(count_allocations([] {
          int* volatile p = new int(1);
          delete p;
        }) == 1);
  CHECK(count_allocations([] {
          void* volatile p = std::malloc(64);
          std::free(p);
        }) == 1);
  CHECK(count_allocations([] {
          void* volatile p = ::operator new(64, std::nothrow);
          ::operator delete(p, std::nothrow);
        }) == 1);
  // An Eigen::VectorXd in a derivative would be caught in Release, where
  // EIGEN_RUNTIME_NO_MALLOC's assertion is compiled out.
  CHECK(count_allocations([] {
          Eigen::VectorXd v = Eigen::VectorXd::Constant(100, 1.0);
          volatile double s = v.sum();
          (void)s;
        }) >= 1);
}

TEST_CASE("the derivative allocates nothing: chains, a branched tree, line forces and world loads") {
  std::mt19937 rng(5);
  const auto arm = models::robot_arm({}, [](double t) { return Vec3d(0, 0, std::sin(t)); });
  const auto chain = models::chain<6, models::runtime_axes>(test::chain_params<6>(rng));
  const auto tree = models::tree<tree_shape>(test::tree_params<tree_shape.n>(rng));
  const auto sprung = sprung_arm();
  std::array<double, 2> x{0.1, 0.2}, dx, z{0.3, 0.4}, dz;
  std::array<double, 12> y{}, dy;
  decltype(tree)::state_type w{}, dw;
  eigen_state<decltype(arm)> xe(0.1, 0.2), dxe;
  for (auto& v : w) v = test::uniform(rng, -1, 1);
  CHECK(count_allocations([&] {
          for (int i = 0; i < 100; ++i) {
            sprung(z, dz, 0.0);
            arm(x, dx, 0.1 * i);
            arm(xe, dxe, 0.1 * i);
            chain(y, dy, 0.0);
            tree(w, dw, 0.0);
            accelerations_articulated_body(chain, 0.0, y.data(), y.data() + 6, dy.data() + 6);
            accelerations_articulated_body(tree, 0.0, w.data(), w.data() + tree_shape.n, dw.data() + tree_shape.n);
          }
        }) == 0);
}

TEST_CASE("a loop scene's derivative, its Jacobian and its projected stepping allocate nothing") {
  const auto fb = models::fourbar({});
  using X = decltype(fb)::state_type;
  X x{0.3, 1.3, 2.4, 5.0, 0, 0}, dx;
  close_loops<"crank_pivot">(fb, x);
  auto dopri = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>());
  integrate_projected(dopri, fb, x, 0.0, 0.01, 1e-3);  // the stepper sizes its buffers
  CHECK(count_allocations([&] {
          for (int i = 0; i < 100; ++i) fb(x, dx, 0.0);
          integrate_projected(dopri, fb, x, 0.01, 0.5, 1e-3);
          normalize(fb, x);
          // by implicit differentiation (its LU on the stack), then dual numbers
          volatile double sink = jacobian(fb, 0.0, x).sum() + jacobian_dual(fb, 0.0, x).sum();
          (void)sink;
        }) == 0);
  jacobian_matrix<std::remove_cvref_t<decltype(fb)>> J;
  CHECK(detail::jacobian_loops(fb, 0.0, x, J));
}

TEST_CASE("a ball bouncing on the ground (a Contact) allocates nothing, in its derivative, its Jacobian and through simulate") {
  const contact_material m{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.8, .dynamic_friction = 0.6};
  const auto ball = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"b">({.m = 1, .J = Mat3d::Identity() * 0.004}),
                          Contact<"ground", contact_shape::sphere, contact_shape::half_space>(
                              {.a = {.radius = 0.1}, .b = {.n = {0, 1, 0}}, .material_a = m, .material_b = m}),
                          connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">,
                          connect<"fly.frame_b", "ground.frame_a">, connect<"world.frame_b", "ground.frame_b">);
  decltype(ball)::state_type x{0, 0.099, 0, 0, 0, 0, 1, 0.5, -0.1, 0.2, 1.0, 2.0, -3.0}, dx;
  // jacobian() takes dual numbers for one link with force elements; the
  // analytic path, with the contact's loads, is called as well.
  static_assert(!detail::jacobian_takes_analytic<std::remove_cvref_t<decltype(ball)>>());
  CHECK(count_allocations([&] {
          for (int i = 0; i < 100; ++i) ball(x, dx, 0.0);
          const auto y = simulate(ball, x, 0.0, 0.5);
          const double j = jacobian(ball, 0.0, x).sum() + detail::jacobian_analytic(ball, 0.0, x).sum();
          volatile double sink = y[1] + dx[1] + j;
          (void)sink;
        }) == 0);
}

TEST_CASE("flange::simulate allocates nothing: the crane (no projection), the four-bar and a free body (projected)") {
  // The default path: its stepper, its per-step check and its replay copy
  // live on the stack (std::array states).
  const auto crane = models::gantry_crane({}, 0.7);
  const auto fb = models::fourbar({});
  const auto body = scene(World<"world">{}, FreeMotion<"fly">{}, Body<"b">({.m = 1, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal()}),
                          connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "b.frame_a">);
  decltype(fb)::state_type xf{0.3, 1.3, 2.4, 5.0, 0, 0};
  close_loops<"crank_pivot">(fb, xf);
  auto xb = neutral_state(body);
  set_joint<"fly">(body, xb, {.R = orientation::cardan(0.2, 0.1, 0.3), .w = Vec3d(3, -2, 5)});
  CHECK(count_allocations([&] {
          const auto a = simulate(crane, {0.2, 0.4, 0.3, -0.5}, 0.0, 2.0);
          const auto b = simulate(fb, xf, 0.0, 0.5);
          const auto c = simulate(body, xb, 0.0, 1.0);
          volatile double sink = a[0] + b[0] + c[0];
          (void)sink;
        }) == 0);
}

TEST_CASE("a trajectory allocates its storage once, before the first step: not per step, not per sample") {
  // The times and the trajectory's two vectors, reserved up front: 3 blocks
  // however many steps and samples (the four-bar: projected samples).
  const auto fb = models::fourbar({});
  decltype(fb)::state_type xf{0.3, 1.3, 2.4, 5.0, 0, 0};
  close_loops<"crank_pivot">(fb, xf);
  long steps_short = 0, steps_long = 0;
  const long short_run = count_allocations([&] { steps_short = simulate(fb, xf, output_times(0.0, 0.1, 0.05)).steps; });
  const long long_run = count_allocations([&] { steps_long = simulate(fb, xf, output_times(0.0, 5.0, 0.001)).steps; });
  CHECK(steps_long > 10 * steps_short);
  CHECK(short_run == 3);
  CHECK(long_run == 3);
}

TEST_CASE("the residual, recovery, the Jacobian and the checked system allocate nothing") {
  std::mt19937 rng(6);
  const auto arm = models::robot_arm();
  const auto tree = models::tree<tree_shape>(test::tree_params<tree_shape.n>(rng));
  const auto chain = models::chain<6, models::runtime_axes>(models::random_chain_params<6>(rng));
  static_assert(detail::analytic_derivatives<std::remove_cvref_t<decltype(chain)>>());  // the analytic Jacobian, too
  decltype(chain)::state_type c{};
  for (auto& v : c) v = test::uniform(rng, -1, 1);
  decltype(tree)::state_type w{}, dw;
  for (auto& v : w) v = test::uniform(rng, -1, 1);
  const std::array<double, 2> x{0.3, 0.1};
  const auto sol = recover(arm, 0.0, x);
  double sum = 0;
  budget b;
  CHECK(count_allocations([&] {
          sum += residual(arm, 0.0, sol.y, sol.yd).sum();
          sum += recover(arm, 0.0, x).energy();
          const auto s = recover(tree, 0.0, w);
          sum += residual(tree, 0.0, s.y, s.yd).sum() + s.energy();
          sum += jacobian(arm, 0.0, x).sum();
          sum += jacobian_finite_difference(arm, 0.0, x).sum();
          sum += jacobian(tree, 0.0, w).sum();
          sum += jacobian(chain, 0.0, c).sum();
          checked(tree, b)(w, dw, 0.0);
          sum += dw[0];
        }) == 0);
  CHECK(std::isfinite(sum));
}

TEST_CASE("every stepping loop allocates nothing once its stepper exists") {
  const auto crane = models::gantry_crane({}, [](double t) { return std::sin(t); });
  using X = decltype(crane)::state_type;
  using E = eigen_state<decltype(crane)>;
  const X x0{0, -0.5, 0, 0};
  X x = x0;
  E xe(0, -0.5, 0, 0);
  odeint::euler<X> euler;
  odeint::runge_kutta4<X> rk4;
  odeint::runge_kutta4<E, double, E, double, odeint::vector_space_algebra> rk4e;
  auto cash_karp = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_cash_karp54<X>());
  auto dopri = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>());
  auto fehlberg = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_fehlberg78<X>());
  auto dense = odeint::make_dense_output(1e-10, 1e-10, odeint::runge_kutta_dopri5<X>());
  odeint::adams_bashforth_moulton<5, X> abm;
  odeint::bulirsch_stoer<X> bs(1e-10, 1e-10);
  odeint::bulirsch_stoer_dense_out<X> bs_dense(1e-10, 1e-10);
  budget b;
  // Steppers size their buffers on first use (Odeint's resizer); a multistep
  // stepper fills its history then: one step of each first.
  euler.do_step(crane, x, 0.0, 1e-3);
  rk4.do_step(crane, x, 0.0, 1e-3);
  rk4e.do_step(crane, xe, 0.0, 1e-3);
  double t = 0, dt = 1e-3;
  cash_karp.try_step(crane, x, t, dt);
  dopri.try_step(crane, x, t, dt);
  fehlberg.try_step(crane, x, t, dt);
  dense.initialize(x, 0.0, 1e-3);
  dense.do_step(crane);
  double t_bs = 0, dt_bs = 1e-3;
  bs.try_step(crane, x, t_bs, dt_bs);
  bs_dense.initialize(x, 0.0, 1e-3);
  bs_dense.do_step(crane);
  double t_abm = 0;
  abm.initialize(crane, x, t_abm, 1e-3);
  X probe;
  double energy = 0;
  const std::array<double, 3> times{0.0, 0.05, 0.1};
  CHECK(count_allocations([&] {
          for (int i = 0; i < 100; ++i) {
            euler.do_step(crane, x, 0.0, 1e-4);
            rk4.do_step(crane, x, 0.0, 1e-4);
            rk4e.do_step(crane, xe, 0.0, 1e-4);
            abm.do_step(crane, x, 0.0, 1e-4);
            cash_karp.try_step(crane, x, t, dt);
            dopri.try_step(crane, x, t, dt);
            fehlberg.try_step(crane, x, t, dt);
            dense.do_step(crane);
            dense.calc_state(dense.current_time() - 0.5 * dense.current_time_step(), probe);
            bs_dense.calc_state(bs_dense.current_time() - 0.5 * bs_dense.current_time_step(), probe);
            rk4.do_step(checked(crane, b), x, 0.0, 1e-4);
          }
          // The integrate functions take their stepper by value: copies of
          // fixed-size steppers stay on the stack.
          X y = x0;
          odeint::integrate_const(rk4, crane, y, 0.0, 0.1, 1e-3);
          odeint::integrate_adaptive(dopri, crane, y, 0.0, 0.1, 1e-3);
          odeint::integrate_times(dense, crane, y, times.begin(), times.end(), 1e-3, [](const X&, double) {});
          odeint::integrate_n_steps(rk4, checked(crane, b), y, 0.0, 1e-3, 50);
          odeint::integrate_const(dense, crane, y, 0.0, 0.1, 1e-2,
                                  record(crane, [&](const auto& sol) { energy += sol.energy(); }));
        }) == 0);
  CHECK(std::isfinite(x[0] + xe(0) + probe[0] + energy));
  // Odeint's Bulirsch–Stoer steppers make two std::vectors (h_opt and work,
  // bulirsch_stoer.hpp) in every step attempt: theirs, not flange's, whose
  // derivative adds none.
  CHECK(count_allocations([&] {
          for (int i = 0; i < 10; ++i) bs.try_step(crane, x, t_bs, dt_bs);
        }) == 2 * 10);
  CHECK(count_allocations([&] {
          for (int i = 0; i < 10; ++i) bs_dense.do_step(crane);
        }) == 2 * 10);
}

TEST_CASE("an ensemble allocates per run, never per case: 10 and 200 cases make the same allocations") {
  auto setup = [](const std::array<double, 1>& c) {
    auto crane = scene(World<"world">({.g = {0, -9.81, 0}}), Prismatic<"rail", axis::x>({.f = 0.0}),
                       Body<"cart">({.m = 1.0, .J = Mat3d::Identity() * 0.1}), Revolute<"pivot", axis::z>{},
                       FixedTranslation<"rope">({.d = {1.0, 0, 0}}), PointMass<"load">({.m = c[0]}),
                       connect<"world.frame_b", "rail.frame_a">, connect<"rail.frame_b", "cart.frame_a">,
                       connect<"rail.frame_b", "pivot.frame_a">, connect<"pivot.frame_b", "rope.frame_a">,
                       connect<"rope.frame_b", "load.frame_a">);
    return std::pair{crane, decltype(crane)::state_type{0.0, -1.0, 0.0, 0.0}};
  };
  namespace en = flange::ensemble;
  auto study = en::make(setup, 0.0, 0.5, {},
                        en::maximum("swing", [](const auto&, double, const auto& x) { return std::abs(x[1]); }),
                        en::crossing("back", [](const auto&, double, const auto& x) { return x[3]; }, 0),
                        en::settling_time("settle", [](const auto&, double, const auto& x) { return x[3]; }, 0.1),
                        en::at_times<2>("s", [](const auto&, double, const auto& x) { return x[0]; }, {0.1, 0.4}),
                        en::final_state{});
  const auto few = en::grid<1>({"m"}, {en::linspace(0.1, 2, 10)});
  const auto many = en::grid<1>({"m"}, {en::linspace(0.1, 2, 200)});
  const en::run_options opt{.block = 16, .progress_line = en::run_options::show::never};
  std::vector<decltype(study)::outcome_type<1>> sink_rows;
  sink_rows.reserve(16);
  auto sink = [&](auto b, auto e) { sink_rows.assign(b, e); };
  // stream() with a sink that keeps one block: what a very large sweep does.
  const long a10 = count_allocations([&] { study.stream(few, en::serial{}, sink, opt); });
  const long a200 = count_allocations([&] { study.stream(many, en::serial{}, sink, opt); });
  INFO("allocations for 10 cases: " << a10 << ", for 200 cases: " << a200);
  CHECK(a10 == a200);
  CHECK(a10 <= 2);  // the block's rows, once
}
