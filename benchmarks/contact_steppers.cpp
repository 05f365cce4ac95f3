// Which stepper for which contact stiffness: a ball thrown onto the ground
// (models/ball.hpp: 1 kg, radius 0.1 m, c = 0.5 s/m, μ = 0.8/0.6), with the
// contact's linear stiffness at rest from 1e3 to 1e8 N/m, simulated for 3 s
// (it bounces, slides, rolls and settles) at tolerance 1e-6 with every
// stepper simulate() offers. Prints, per stiffness and stepper, the median
// wall time of 3 runs, the steps and evaluations, and the height at the
// end against Hertz's rest height:
//   contact_stepper k=<N/m> method=<name> ms=<x> steps=<n> evals=<n> height_error=<m>
// and, per stiffness, the faster of dopri5 and rosenbrock4:
//   contact_stepper k=<N/m> fastest=<name> ratio=<slower/faster>
//
//   build/benchmarks/contact_steppers [tolerance, default 1e-6]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <flange/flange.hpp>
#include <flange/models/ball.hpp>
#include <flange/simulate/bulirsch_stoer.hpp>
#include <flange/simulate/rosenbrock4.hpp>

using namespace flange;

namespace {
struct run_cost {
  double ms = 0;
  long steps = 0, evals = 0;
  double height = 0;
};

template <class Method, class S>
run_cost measure(const S& s, double tol) {
  const typename S::state_type x0{0, 0.3, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 0, 5.0};
  std::vector<double> ms;
  run_cost r;
  for (int k = 0; k < 3; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto tr = simulate<Method>(s, x0, std::vector<double>{0.0, 3.0}, {.tolerance = tol, .max_rhs_evals = 50'000'000});
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    r.steps = tr.steps;
    r.evals = tr.rhs_evals;
    r.height = tr.x.back()[1];
  }
  std::sort(ms.begin(), ms.end());
  r.ms = ms[1];
  return r;
}
}  // namespace

int main(int argc, char** argv) {
  const double tol = argc > 1 ? std::atof(argv[1]) : 1e-6;
  for (double k : {1e3, 1e4, 1e5, 1e6, 1e7, 1e8}) {
    models::ball_params p;
    p.material.stiffness = models::stiffness_for(p, k);
    const auto s = models::ball_on_ground(p);
    const double rest = p.radius - models::rest_depth(p);
    auto line = [&](const char* name, const run_cost& r) {
      std::printf("contact_stepper k=%.0e method=%s ms=%.2f steps=%ld evals=%ld height_error=%.1e\n", k, name, r.ms,
                  r.steps, r.evals, r.height - rest);
    };
    const run_cost d = measure<method::dopri5>(s, tol);
    line("dopri5", d);
    const run_cost b = measure<method::bulirsch_stoer>(s, tol);
    line("bulirsch_stoer", b);
    const run_cost r = measure<method::rosenbrock4>(s, tol);
    line("rosenbrock4", r);
    std::printf("contact_stepper k=%.0e fastest=%s ratio=%.2f\n", k, d.ms <= r.ms ? "dopri5" : "rosenbrock4",
                std::max(d.ms, r.ms) / std::min(d.ms, r.ms));
    std::fflush(stdout);
  }
}
