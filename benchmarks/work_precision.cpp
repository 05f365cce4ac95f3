// Work-precision study: every Boost.Odeint stepper that applies, on seven
// flange scenes, error at the final time against cost.
//
//   build/benchmarks/work_precision [--quick] [--csv FILE] [--scene NAME]
//
// Per point (a tolerance for controlled steppers, a step size for fixed-step
// ones): the scaled error at the final time against a long-double reference
// (flange/study/work_precision.hpp), the median wall time per simulated
// second, derivative evaluations, steps, rejected steps and Jacobians.
// Peer simulators (MuJoCo, Simbody), when they were found at configure time,
// are run as separate programs on the same scenes and the same reference;
// their rows join the same table and CSV.
//
// The summary at the end gives, per scene and accuracy band, the cheapest
// stepper: docs/accuracy-vs-cost.md is written from it.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <flange/flange.hpp>
#include <flange/models/chain.hpp>
#include <flange/models/ball.hpp>
#include <flange/models/legged.hpp>
#include <flange/models/paper.hpp>
#include <flange/simulate/rosenbrock4.hpp>
#include <flange/study/work_precision.hpp>
#include <boost/numeric/odeint.hpp>  // all of Odeint: the steppers flange.hpp leaves out

using namespace flange;

namespace {

struct options {
  bool quick = false;
  std::string csv, scene, reference_out;
};

template <class X>
void keep(const X& x) {
  asm volatile("" : : "r"(&x) : "memory");  // the result is used: the run cannot be optimised away
}

/// The study of one scene; symplectic = its Hamiltonian is separable
/// (constant mass matrix, no velocity-dependent forces).
template <class S>
void study_scene(const std::string& name, const S& s, typename S::state_type x0, double T, bool symplectic,
                 const options& o, std::vector<study::point>& out, std::ostream& refs,
                 study::reference_stepper reference = study::reference_stepper::fehlberg78) {
  if (!o.scene.empty() && o.scene != name) return;
  using X = typename S::state_type;
  const auto ref = study::long_double_reference(s, x0, T, 1e-18L, 1e-17L, reference);
  std::cout << "\n## " << name << ": " << S::n_v << " degrees of freedom, T = " << T << " s\n"
            << "reference: " << (reference == study::reference_stepper::dopri5 ? "dopri5" : "fehlberg78")
            << " in long double at 1e-18 (" << ref.rhs_evals
            << " evaluations for two solves), its error estimate " << std::setprecision(2) << ref.error_estimate
            << "\n";
  refs << name << ' ' << T;
  for (double v : x0) refs << ' ' << std::setprecision(17) << v;
  for (long double v : ref.x) refs << ' ' << std::setprecision(20) << v;
  refs << '\n';
  std::cout << std::setw(34) << std::left << "stepper" << std::right << std::setw(10) << "tol/dt" << std::setw(11)
            << "error" << std::setw(13) << "s/sim s" << std::setw(10) << "evals" << std::setw(9) << "steps"
            << std::setw(9) << "rejected" << std::setw(7) << "jac" << "\n";
  const int repeats = o.quick ? 3 : 5;
  const double min_sample = o.quick ? 5e-4 : 3e-3;
  auto add = [&](const std::string& stepper, const char* control, double tol, auto run) {
    X x = x0;
    auto left_out = [&](const std::string& why) {
      std::cout << std::setw(34) << std::left << stepper << std::right << std::setw(10) << std::setprecision(1)
                << tol << "  left out: " << why << "\n";
    };
    study::cost c;
    try {
      c = run(x);
    } catch (const std::exception& ex) {  // a NaN state ends in a singular mass matrix
      left_out(std::string("the run failed: ") + ex.what());
      return;
    }
    const double e = study::scaled_error(x, ref.x);
    if (!std::isfinite(e)) return left_out("the state is not finite (unstable)");
    if (e > 1) return left_out("error > 1, no accuracy at all");
    const double sec = study::median_seconds(
                           [&] {
                             X y = x0;
                             keep(run(y));
                             keep(y);
                           },
                           repeats, min_sample) /
                       T;
    out.push_back({name, stepper, control, tol, e, sec, c});
    std::cout << std::setw(34) << std::left << stepper << std::right << std::setprecision(1) << std::setw(10) << tol
              << std::setprecision(2) << std::setw(11) << e << std::setw(13) << sec << std::setw(10) << c.rhs_evals
              << std::setw(9) << c.steps << std::setw(9) << c.rejected << std::setw(7) << c.jacobian_evals << "\n";
  };

  std::vector<double> tols;
  for (int k = 3; k <= 12; k += o.quick ? 3 : 1) tols.push_back(std::pow(10.0, -k));
  auto controlled = [&](const char* stepper, auto make) {
    for (double tol : tols)
      add(stepper, "tol", tol, [&](X& x) { return study::integrate_controlled(make(tol), s, x, 0.0, T, 1e-3); });
  };
  controlled("runge_kutta_cash_karp54",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<X>()); });
  controlled("runge_kutta_dopri5",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<X>()); });
  controlled("runge_kutta_fehlberg78",
             [](double tol) { return odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<X>()); });
  controlled("bulirsch_stoer", [](double tol) { return odeint::bulirsch_stoer<X>(tol, tol); });
  // rosenbrock4 with the exact Jacobian (dual numbers), and with central
  // differences in its place; the latter's evaluations include the 2·(n + 1)
  // of each Jacobian.
  auto stiff = [&](const char* stepper, auto method) {
    for (double tol : tols)
      add(stepper, "tol", tol, [&](X& x) {
        stiff_stats st;
        integrate_rosenbrock4<decltype(method)>(s, x, 0.0, T, 1e-3, tol, tol, nullptr, 0.0, &st);
        long evals = st.rhs_evals;
        if constexpr (std::is_same_v<decltype(method), jacobian_method::finite_difference>)
          evals += 2 * (S::n_state + 1) * st.jacobian_evals;
        return study::cost{evals, st.steps, st.jacobian_evals - st.steps, st.jacobian_evals};
      });
  };
  stiff("rosenbrock4 (exact Jacobian)", jacobian_method::exact{});
  stiff("rosenbrock4 (finite-difference Jacobian)", jacobian_method::finite_difference{});

  // Fixed steps: dt = T / n over a geometric sweep of n.
  auto fixed = [&](const char* stepper, auto make, double dt_max, double dt_min) {
    const double factor = o.quick ? 10.0 : std::sqrt(10.0);
    for (double dt = dt_max; dt >= dt_min * 0.999; dt /= factor) {
      const long n = std::max(1L, std::lround(T / dt));
      add(stepper, "dt", T / n, [&](X& x) { return study::integrate_fixed(make(), s, x, 0.0, T, n); });
    }
  };
  fixed("euler", [] { return odeint::euler<X>(); }, 1e-2, o.quick ? 1e-5 : 1e-6);
  fixed("runge_kutta4", [] { return odeint::runge_kutta4<X>(); }, 1e-1, 1e-4);
  fixed("adams_bashforth_moulton<5>", [] { return odeint::adams_bashforth_moulton<5, X>(); }, 1e-1, 1e-4);

  if constexpr (S::n_q == 1) {
    if (symplectic) {
      // H = p²/(2I) + V(q): with p = I·q̇, q̇ = p/I and ṗ = I·q̈(q). The scene's
      // q̈ does not depend on q̇ (one joint, no damping), so the derivative
      // at (q, 0) is the force. Positions q, "momenta" q̇ (I folded in).
      using Q = std::array<double, 1>;
      auto run_symplectic = [&](auto stepper, long n) {
        return [&s, stepper, n, T](X& x) mutable {
          study::cost c;
          Q q{x[0]}, p{x[1]};
          auto coordinate = [](const Q& pp, Q& dq) { dq[0] = pp[0]; };
          auto momentum = [&](const Q& qq, Q& dp) {
            ++c.rhs_evals;
            X y{qq[0], 0.0}, dy;
            s(y, dy, 0.0);
            dp[0] = dy[1];
          };
          const double dt = T / n;
          for (long i = 0; i < n; ++i)
            stepper.do_step(std::make_pair(coordinate, momentum), std::make_pair(std::ref(q), std::ref(p)), i * dt, dt);
          c.steps = n;
          x = X{q[0], p[0]};
          return c;
        };
      };
      auto sweep = [&](const char* stepper, auto make) {
        const double factor = o.quick ? 10.0 : std::sqrt(10.0);
        for (double dt = 1e-1; dt >= 1e-4 * 0.999; dt /= factor) {
          const long n = std::max(1L, std::lround(T / dt));
          add(stepper, "dt", T / n, run_symplectic(make(), n));
        }
      };
      sweep("symplectic_euler", [] { return odeint::symplectic_euler<Q>(); });
      sweep("symplectic_rkn_sb3a_mclachlan", [] { return odeint::symplectic_rkn_sb3a_mclachlan<Q>(); });
    }
  }
  if (!symplectic)
    std::cout << "symplectic steppers: not applicable, the Hamiltonian is not separable "
              << (S::n_v > 1 ? "(the mass matrix depends on q)" : "(velocity-dependent forces)") << "\n";
}

/// Runs a peer simulator's program on the references and reads its CSV rows.
[[maybe_unused]] void run_peer(const char* exe, const std::string& refs_file, const options& o, std::vector<study::point>& out) {
  std::string cmd = std::string(exe) + " --reference " + refs_file + (o.quick ? " --quick" : "");
  if (!o.scene.empty()) cmd += " --scene " + o.scene;
  std::cout << "\n## peer: " << cmd << "\n" << std::flush;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) {
    std::cout << "could not start it\n";
    return;
  }
  char line[4096];
  while (std::fgets(line, sizeof line, pipe)) {
    if (std::strncmp(line, "row,", 4) != 0) {
      std::cout << line;  // the peer's own notes
      continue;
    }
    std::stringstream ss(line + 4);
    study::point p;
    std::string f[10];
    for (auto& v : f) std::getline(ss, v, ',');
    p.scene = f[0], p.stepper = f[1], p.control = f[2];
    p.tolerance = std::stod(f[3]), p.error = std::stod(f[4]), p.seconds_per_sim_second = std::stod(f[5]);
    p.c = {std::stol(f[6]), std::stol(f[7]), std::stol(f[8]), std::stol(f[9])};
    std::cout << std::setw(34) << std::left << (p.scene + " " + p.stepper) << std::right << std::setprecision(1)
              << std::setw(10) << p.tolerance << std::setprecision(2) << std::setw(11) << p.error << std::setw(13)
              << p.seconds_per_sim_second << std::setw(10) << p.c.rhs_evals << std::setw(9) << p.c.steps << "\n";
    out.push_back(p);
  }
  if (pclose(pipe) != 0) std::cout << "the peer program failed\n";
}

}  // namespace

int main(int argc, char** argv) {
  options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      o.quick = true;
    else if (a == "--csv" && i + 1 < argc)
      o.csv = argv[++i];
    else if (a == "--scene" && i + 1 < argc)
      o.scene = argv[++i];
    else if (a == "--reference-out" && i + 1 < argc)
      o.reference_out = argv[++i];
    else {
      std::cerr << "usage: work_precision [--quick] [--csv FILE] [--scene NAME] [--reference-out FILE]\n"
                   "scenes: robot_arm gantry_crane double_pendulum spatial_chain4 stiff_joint free_body fourbar legged\n"
                   "        bouncing_ball box_slide legged_stand\n";
      return 2;
    }
  }
  std::vector<study::point> points;
  const std::string refs_file = o.reference_out.empty() ? "work_precision_references.txt" : o.reference_out;
  {
    std::ofstream refs(refs_file);
    refs << "# scene T x0... reference(T)...: flange's long-double references, read by the peer programs\n";

    // The paper's arm, swinging freely from 57° above horizontal (θ0 = 2.6 rad).
    study_scene("robot_arm", models::robot_arm(), {1.0, 0.0}, 5.0, true, o, points, refs);
    // The paper's crane, the load released at θ = 1 rad with the cart moving.
    study_scene("gantry_crane", models::gantry_crane(), {0.0, 1.0 - M_PI / 2, 0.5, 0.0}, 5.0, false, o, points, refs);
    {
      // A double pendulum released from near upright: chaotic.
      models::chain_params<2> p;
      for (int i = 0; i < 2; ++i) {
        p.d[i] = Vec3d(1, 0, 0);
        p.m[i] = 1;
        p.J[i] = Mat3d::Identity() * 0.01;
      }
      study_scene("double_pendulum", models::chain<2, models::planar_axes>(p), {2.5, 0.5, 0.0, 0.0}, 5.0, false, o,
                  points, refs);
    }
    {
      // Four links, non-parallel run-time axes, offsets out of the plane.
      models::chain_params<4> p;
      p.axis = {Vec3d(0, 0, 1), Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(1, 1, 1).normalized()};
      for (int i = 0; i < 4; ++i) {
        p.d[i] = Vec3d(0.4, 0.1 * (i % 2), -0.05 * i);
        p.m[i] = 1.0 - 0.15 * i;
        p.J[i] = Vec3d(0.01, 0.02, 0.015).asDiagonal();
      }
      study_scene("spatial_chain4", models::chain<4, models::runtime_axes>(p), {0.3, -0.4, 0.5, 0.2, 0, 0, 0, 0},
                  3.0, false, o, points, refs);
    }
    {
      // A pendulum with a stiff, critically damped elbow spring (ω ≈ 2900 rad/s
      // against the swing's ≈ 3 rad/s): the fast mode dies in a millisecond, then
      // only stability holds explicit steppers back.
      const double c = 1e6, I2 = 0.005 + 0.5 * 0.25;
      const auto stiff = scene(
          World<"world">({.g = {0, -9.81, 0}}), Revolute<"shoulder", axis::z>{},
          FixedTranslation<"upper">({.d = {1, 0, 0}}), Body<"b1">({.m = 1.0, .J = Mat3d::Identity() * 0.01}),
          Revolute<"elbow", axis::z, axis_law::spring_damper>({.c = c, .d = 2 * std::sqrt(c * I2), .phi0 = 0.0}),
          FixedTranslation<"lower">({.d = {0.5, 0, 0}}), Body<"b2">({.m = 0.5, .J = Mat3d::Identity() * 0.005}),
          connect<"world.frame_b", "shoulder.frame_a">, connect<"shoulder.frame_b", "upper.frame_a">,
          connect<"upper.frame_b", "b1.frame_a">, connect<"upper.frame_b", "elbow.frame_a">,
          connect<"elbow.frame_b", "lower.frame_a">, connect<"lower.frame_b", "b2.frame_a">);
      study_scene("stiff_joint", stiff, {0.5, 0.3, 0.0, 0.0}, 2.0, false, o, points, refs);
    }
    {
      // An asymmetric body thrown under gravity on a FreeMotion, its centre of
      // mass off its frame, spinning near its intermediate axis (it flips).
      const auto free_body =
          scene(World<"world">{}, FreeMotion<"fly">{},
                Body<"body", cm::offset>({.m = 2.0, .J = Vec3d(0.1, 0.2, 0.3).asDiagonal(), .r_cm = {0.1, 0, 0}}),
                connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "body.frame_a">);
      auto x0 = neutral_state(free_body);
      set_joint<"fly">(free_body, x0,
                       {.r = Vec3d::Zero(), .v = Vec3d(1, 2, 0), .R = orientation{}, .w = Vec3d(0.3, 4, 0.2)});
      study_scene("free_body", free_body, x0, 5.0, false, o, points, refs);
    }
    {
      // A closed loop: the crank-rocker four-bar (models/linkages.hpp), free
      // under gravity from θ2 = 1 rad at 3 rad/s, its loop closed. The plain
      // ODE form (no projection between steps) for every stepper.
      const models::fourbar_params p{};
      const auto fb = models::fourbar(p);
      const auto q = models::fourbar_coordinates(p, 1.0, models::freudenstein_rocker(p, 1.0));
      std::array<double, 6> x0{q[0], q[1], q[2], 3.0, 0, 0};
      close_loops<"crank_pivot">(fb, x0);
      study_scene("fourbar", fb, x0, 5.0, false, o, points, refs);
    }
    {
      // A floating-base robot falling freely: a trunk on a FreeMotion with four
      // legs of three revolute joints (models/legged.hpp), every coordinate and
      // rate moved off neutral.
      const auto legged = models::legged<4, 3>();
      auto x0 = neutral_state(legged);
      for (std::size_t i = 0; i < x0.size(); ++i) x0[i] += 0.3 * std::sin(1.3 * i + 0.4);
      normalize(legged, x0);
      study_scene("legged", legged, x0, 2.0, false, o, points, refs);
    }
    {
      // Contact: a ball thrown onto the ground (models/ball.hpp: Hunt–Crossley
      // at E = 1e7 Pa, about 3e6 N/m at rest, with Stribeck friction): it
      // lands twice, skidding, and rolls. The contact scenes' references are
      // dopri5's (study/work_precision.hpp: fehlberg78's error estimate can
      // step over a landing).
      const auto ball = models::ball_on_ground();
      study_scene("bouncing_ball", ball, {0, 0.3, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 0, 5.0}, 1.0, false, o, points,
                  refs, study::reference_stepper::dopri5);
    }
    {
      // Contact: a box sliding on its face at 1 m/s, its eight corners'
      // spheres against the ground, until friction stops it.
      const contact_material m{.stiffness = 1e7, .dissipation = 0.5, .static_friction = 0.5, .dynamic_friction = 0.5};
      const auto box = scene(
          World<"world">{}, FreeMotion<"fly">{}, Body<"box">({.m = 2.0, .J = Vec3d(0.02, 0.04, 0.03).asDiagonal()}),
          Contact<"box_ground", contact_shape::box, contact_shape::half_space>(
              {.a = {.half_extents = {0.2, 0.1, 0.15}, .corner_radius = 0.01}, .b = {.n = {0, 1, 0}},
               .material_a = m, .material_b = m, .transition_velocity = 1e-3}),
          connect<"world.frame_b", "fly.frame_a">, connect<"fly.frame_b", "box.frame_a">,
          connect<"fly.frame_b", "box_ground.frame_a">, connect<"world.frame_b", "box_ground.frame_b">);
      study_scene("box_slide", box, {0, 0.0995, 0, 0, 0, 0, 1, 1.0, 0, 0, 0, 0, 0}, 0.5, false, o, points, refs,
                  study::reference_stepper::dopri5);
    }
    {
      // Contact: the quadruped (models/legged.hpp) dropped onto its feet in a
      // crouch, standing under one PD law on its twelve joints.
      const auto robot = models::legged<4, 3, true, true>({.transition_velocity = 0.03}, models::crouch_drive{});
      study_scene("legged_stand", robot, models::crouched_state(robot), 1.0, false, o, points, refs,
                  study::reference_stepper::dopri5);
    }
  }
#ifdef FLANGE_PEER_MUJOCO
  run_peer(FLANGE_PEER_MUJOCO, refs_file, o, points);
#else
  std::cout << "\n## peer: MuJoCo not found at configure time (apt-get install libmujoco-dev): skipped\n";
#endif
#ifdef FLANGE_PEER_SIMBODY
  run_peer(FLANGE_PEER_SIMBODY, refs_file, o, points);
#else
  std::cout << "\n## peer: Simbody not found at configure time (apt-get install libsimbody-dev): skipped\n";
#endif

  if (!o.csv.empty()) {
    std::ofstream csv(o.csv);
    csv << "scene,stepper,control,tolerance,error,seconds_per_sim_second,rhs_evals,steps,rejected,jacobian_evals\n";
    csv << std::setprecision(6);
    for (const auto& p : points)
      csv << p.scene << ',' << p.stepper << ',' << p.control << ',' << p.tolerance << ',' << p.error << ','
          << p.seconds_per_sim_second << ',' << p.c.rhs_evals << ',' << p.c.steps << ',' << p.c.rejected << ','
          << p.c.jacobian_evals << '\n';
    std::cout << "\nwrote " << points.size() << " points to " << o.csv << "\n";
  }

  // The answer: the cheapest stepper per scene, accuracy band and simulator
  // (peer rows are named "mujoco: …", "simbody: …").
  auto simulator = [](const study::point& p) {
    const auto colon = p.stepper.find(':');
    return colon == std::string::npos ? std::string("flange") : p.stepper.substr(0, colon);
  };
  std::cout << "\n## cheapest per accuracy band (error ≤ band; time per simulated second, median)\n\n"
            << "| scene | band | simulator | stepper | tol/dt | error | µs per simulated s | evaluations |\n"
            << "|---|---|---|---|---|---|---|---|\n";
  std::vector<std::pair<std::string, std::string>> groups;
  for (const auto& p : points)
    if (std::find(groups.begin(), groups.end(), std::pair(p.scene, simulator(p))) == groups.end())
      groups.emplace_back(p.scene, simulator(p));
  for (const auto& [sc, sim] : groups)
    for (double band : {1e-3, 1e-6, 1e-9, 1e-12}) {
      std::vector<study::point> mine;
      for (const auto& p : points)
        if (simulator(p) == sim) mine.push_back(p);
      std::cout << "| " << sc << " | " << std::setprecision(0) << std::scientific << band << std::defaultfloat
                << " | " << sim << " | ";
      if (const auto* p = study::cheapest(mine, sc, band))
        std::cout << p->stepper << " | " << p->control << ' ' << std::setprecision(1) << p->tolerance << " | "
                  << std::setprecision(2) << p->error << " | " << std::setprecision(3)
                  << p->seconds_per_sim_second * 1e6 << " | " << p->c.rhs_evals << " |\n";
      else
        std::cout << "none reached it | | | | |\n";
    }
  return 0;
}
