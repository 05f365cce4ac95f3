// Your own mechanism: a 3-joint spatial arm (docs/tutorial.md). Each joint is
// driven by its own PD law, written by joint name; the links are a steel box
// and two aluminium tubes whose mass and inertia flange computes from their
// shape. Seven components and six connections.
//
//   spatial_arm                  simulate 4 s, write spatial_arm.csv, print a summary
//   spatial_arm --equations      print the arm's equations
//   spatial_arm --csv FILE       write the trajectory to FILE
//   spatial_arm --html FILE      also write a page that plays the motion in 3-D (flange/viewer/,
//                                three.js from tools/install-deps.sh --viewer)
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>

#include <flange/flange.hpp>
#include <flange/viewer/recording.hpp>

#include "spatial_arm.hpp"

using namespace flange;

int main(int argc, char** argv) {
  const char* csv = "spatial_arm.csv";
  const char* html = nullptr;
  bool equations = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--equations")) equations = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--html") && i + 1 < argc) html = argv[++i];
    else return std::cerr << "usage: spatial_arm [--equations] [--csv FILE] [--html FILE]\n", 2;
  }

  // The arm and its PD laws by joint name (examples/spatial_arm.hpp).
  const auto arm = spatial_arm::make_scene();
  using Arm = decltype(arm);

  if (equations) {
    print_equations(arm, std::cout);
    return 0;
  }

  // Start with the elbow bent down and the wrist straight; the shoulder at 0.
  const auto x0 = initial_state<"elbow">(arm, {.q = 0.6});
  // The states every 10 ms (checked, and failing loudly with t, x and the reason).
  const auto run = simulate(arm, x0, output_times(0.0, 4.0, 0.01), {.tolerance = 1e-9, .max_rhs_evals = 1'000'000});
  std::ofstream out(csv);
  out << "t,shoulder,elbow,wrist,tip_x,tip_y,tip_z\n";
  viewer::recording page(arm);  // plots the three joint angles under the 3-D view
  for (std::size_t k = 0; k < run.size(); ++k) {
    const auto s = recover(arm, run.t[k], run.x[k]);  // every variable of the DAE at that sample
    page.add(s);
    const Vec3d tip = s.frame("hand.frame_b").r;
    out << s.t << ',' << internal<"shoulder", "phi">(s) << ',' << internal<"elbow", "phi">(s) << ','
        << internal<"wrist", "phi">(s) << ',' << tip.x() << ',' << tip.y() << ',' << tip.z() << '\n';
  }
  const auto& x = run.x.back();

  const auto end = recover(arm, 4.0, x);
  if (html) {
    page.write_html(html, viewer::three_js(), "flange: a 3-joint spatial arm");
    std::cout << "wrote " << html << " (" << page.samples() << " samples)\n";
  }
  std::cout << "flange spatial arm: " << Arm::n_equations << " equations, " << Arm::n_unknowns
            << " unknowns, 3 joints driven by PD laws read by name\n"
            << "  link masses: upper " << arm.get<"upper">().m() << " kg, fore " << arm.get<"fore">().m()
            << " kg, hand " << arm.get<"hand">().m() << " kg (from their shapes)\n"
            << "  after 4 s: shoulder " << x[0] << " rad (target 1.0), elbow " << x[1] << " rad (target −0.8), wrist "
            << x[2] << " rad (target 0.4)\n"
            << "  largest scaled residual at the end " << scaled_residual(arm, end) << "\n";
  return 0;
}
