// Work-precision study: every Boost.Odeint stepper that applies, on eleven
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

#include "work_precision_study.hpp"

using namespace flange;
using namespace work_precision;

namespace {

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

    study_chains(o, points, refs);
    study_bodies(o, points, refs);
    study_contact(o, points, refs);
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
