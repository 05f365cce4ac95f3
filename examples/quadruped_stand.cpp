// A quadruped dropped onto the ground stands up on its feet: a floating
// trunk with four 3-joint legs (models::legged), a sphere at each foot and
// a box for its belly, each a Contact with the ground. One PD law drives
// every joint, reading the joint by its name, toward a crouch (knees 0.4
// rad, ankles −0.8 rad: each foot under its hip). It lands, sways, and
// settles with its weight on its four feet.
//
//   quadruped_stand                 simulate 3 s, write quadruped_stand.csv, print a summary
//   quadruped_stand --equations     print the equations
//   quadruped_stand --csv FILE      write the trajectory to FILE
//   quadruped_stand --html FILE     also write a page that plays the motion in 3-D
//   quadruped_stand --gains 0       the same with zero gains: it folds onto its belly
//
// The CSV has t, the trunk's height, the four feet's normal forces, their
// sum over the robot's weight, and the belly's deepest corner.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>

#include <flange/flange.hpp>
#include <flange/models/legged.hpp>
#include <flange/viewer/recording.hpp>

using namespace flange;

int main(int argc, char** argv) {
  const char* csv = "quadruped_stand.csv";
  const char* html = nullptr;
  bool equations = false;
  double gains = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--equations")) equations = true;
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) csv = argv[++i];
    else if (!std::strcmp(argv[i], "--html") && i + 1 < argc) html = argv[++i];
    else if (!std::strcmp(argv[i], "--gains") && i + 1 < argc) gains = std::atof(argv[++i]);
    else return std::cerr << "usage: quadruped_stand [--equations] [--csv FILE] [--html FILE] [--gains SCALE]\n", 2;
  }
  // Rubber feet (a 3 cm sphere each) on the ground 0.78 m below the trunk's
  // centre: with straight legs the feet just touch it.
  const models::legged_params p{.transition_velocity = 0.03};
  const auto robot = models::legged<4, 3, true, true>(p, models::crouch_drive{.kp = 1000 * gains, .kd = 50 * gains});
  using Robot = decltype(robot);
  if (equations) {
    print_equations(robot, std::cout);
    return 0;
  }
  // Crouched, its feet 4 cm above the ground, at rest.
  const auto x0 = models::crouched_state(robot);
  const auto run = simulate(robot, x0, output_times(0.0, 3.0, 0.005), {.tolerance = 1e-9});

  const double weight = (p.trunk_mass + 12 * p.link_mass) * 9.81;
  auto feet = [](const auto& s) {
    return std::array{internal<"foot0", "f_n">(s), internal<"foot1", "f_n">(s), internal<"foot2", "f_n">(s),
                      internal<"foot3", "f_n">(s)};
  };
  auto belly = [](const auto& s) {
    return std::max({internal<"belly", "δ[0]">(s), internal<"belly", "δ[1]">(s), internal<"belly", "δ[4]">(s),
                     internal<"belly", "δ[5]">(s)});
  };
  std::ofstream out(csv);
  out << "t,height,foot0,foot1,foot2,foot3,feet_over_weight,belly_depth\n";
  out.precision(10);
  viewer::recording page(robot);
  page.plot("trunk height [m]", [](const auto& s) { return s.frame("trunk.frame_a").r.y(); })
      .plot("feet / weight", [&](const auto& s) {
        const auto f = feet(s);
        return (f[0] + f[1] + f[2] + f[3]) / weight;
      });
  for (std::size_t k = 0; k < run.size(); ++k) {
    const auto s = recover(robot, run.t[k], run.x[k]);
    page.add(s);
    const auto f = feet(s);
    out << s.t << ',' << run.x[k][1] << ',' << f[0] << ',' << f[1] << ',' << f[2] << ',' << f[3] << ','
        << (f[0] + f[1] + f[2] + f[3]) / weight << ',' << belly(s) << '\n';
  }
  const auto end = recover(robot, 3.0, run.x.back());
  const auto f = feet(end);
  // The height over the last second: steady once it stands.
  double lo = 1, hi = -1;
  for (std::size_t k = 0; k < run.size(); ++k)
    if (run.t[k] >= 2.0) lo = std::min(lo, run.x[k][1]), hi = std::max(hi, run.x[k][1]);
  if (html) {
    page.write_html(html, viewer::three_js(), "flange: a quadruped stands");
    std::cout << "wrote " << html << " (" << page.samples() << " samples)\n";
  }
  std::cout << "flange quadruped: " << Robot::n_q << " coordinates, " << Robot::n_v
            << " rates, 5 contacts (four feet, the belly); one PD law on its 12 joints, by name\n"
            << "  dropped 4 cm in a crouch, 3 s (dopri5, tol 1e-9, " << run.rhs_evals << " evaluations)\n"
            << "  trunk height " << run.x.back()[1] << " m, within " << hi - lo << " m over the last second\n"
            << "  feet carry " << f[0] << ", " << f[1] << ", " << f[2] << ", " << f[3] << " N: "
            << (f[0] + f[1] + f[2] + f[3]) / weight << " of its weight; the belly "
            << (belly(end) > 0 ? "on the ground" : "clear of it") << "\n"
            << "  largest scaled residual at the end " << scaled_residual(robot, end) << "\n"
            << "  wrote " << csv << "\n";
  if (gains == 0) return belly(end) > 0 && run.x.back()[1] > -p.ground_depth ? 0 : 1;
  return hi - lo < 1e-6 && std::abs((f[0] + f[1] + f[2] + f[3]) / weight - 1) < 1e-6 && belly(end) == 0 ? 0 : 1;
}
