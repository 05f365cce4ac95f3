// What the peer-simulator programs share: reading flange's long-double
// references, the scaled error, the median timing, and the row format that
// benchmarks/work_precision.cpp reads back. Plain C++17 and no flange header,
// so a peer whose own headers need C++17 (Simbody 3.7) can include it.
//
// The scenes are the paper's, with flange::models' default parameters:
//   robot_arm     m = 1 kg at d = 0.5 m, J = diag(0.01, 0.02, 0.02) kg m² about
//                 the body's centre, g = 9.81 m/s² along −y, no motor torque;
//                 x = (φ, φ̇), φ = 0 with the arm horizontal along +x
//   gantry_crane  cart M = 1 kg (J = 0.1·1), load m = 0.5 kg (a point mass) on a
//                 d = 1 m rope, no force; x = (s, φ, ṡ, φ̇)
//   free_body     a body on a FreeMotion: m = 2 kg, centre of mass at (0.1, 0, 0)
//                 in its frame, J = diag(0.1, 0.2, 0.3) kg m² about it, gravity;
//                 x = (r, Qx, Qy, Qz, Qw, v, ω): r and v the frame origin's
//                 position and velocity in the world, ω in body axes
//   legged        models::legged<4, 3>(): a trunk (10 kg, J = diag(0.1, 0.3,
//                 0.25)) on a FreeMotion, four legs at (±0.3, 0, ±0.15), each of
//                 three 0.25 m links (0.6 kg at mid-link, J = diag(0.004,
//                 0.0005, 0.004)), the hip about y, knee and ankle about x;
//                 x = (trunk as free_body, 12 joint angles, 12 joint rates)
//   fourbar       models::fourbar({}): a crank-rocker four-bar of uniform bars
//                 (I = m·L²/12 about the centre across, 1e-3 of that about the
//                 bar's axis): crank a = 0.3 m, 1 kg, about z at the origin;
//                 coupler b = 1 m, 2 kg; rocker c = 0.8 m, 1.5 kg, whose end is
//                 pinned at (d, 0, 0), d = 1 m; x = the tree's (θ2, θ3 − θ2,
//                 rocker − θ3, rates), the loop closed at x0
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace peer {

inline const double arm_m = 1.0, arm_d = 0.5, arm_Jx = 0.01, arm_Jz = 0.02, g = 9.81;
inline const double crane_M = 1.0, crane_m = 0.5, crane_d = 1.0;
inline const double free_m = 2.0, free_cm = 0.1, free_J[3] = {0.1, 0.2, 0.3};
inline const double legged_trunk_m = 10.0, legged_trunk_J[3] = {0.1, 0.3, 0.25}, legged_link_m = 0.6,
                    legged_link_L = 0.25, legged_link_J[3] = {0.004, 0.0005, 0.004}, legged_hip_x = 0.3,
                    legged_hip_z = 0.15;

inline const double fourbar_d = 1.0, fourbar_a = 0.3, fourbar_b = 1.0, fourbar_c = 0.8, fourbar_ma = 1.0,
                    fourbar_mb = 2.0, fourbar_mc = 1.5;

struct reference {
  double T = 0;
  std::vector<double> x0;
  std::vector<long double> x;  // the state at T
};

/// The references file flange's work_precision writes: per line a scene
/// name, T, the initial state and the reference state at T.
inline std::map<std::string, reference> read_references(const std::string& file, const std::map<std::string, int>& n_state) {
  std::map<std::string, reference> out;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string name;
    reference r;
    ss >> name >> r.T;
    const auto n = n_state.find(name);
    if (n == n_state.end()) continue;
    r.x0.resize(n->second);
    r.x.resize(n->second);
    for (auto& v : r.x0) ss >> v;
    for (auto& v : r.x) ss >> v;
    if (ss) out[name] = r;
  }
  return out;
}

/// max_i |x_i − r_i| / (1 + |r_i|), as flange::study::scaled_error measures it.
inline double scaled_error(const std::vector<double>& x, const std::vector<long double>& r) {
  double worst = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!std::isfinite(x[i])) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, static_cast<double>(std::abs(x[i] - r[i]) / (1 + std::abs(r[i]))));
  }
  return worst;
}

/// Median over `repeats` of the seconds one run() takes; each sample repeats
/// run() until it lasts min_sample seconds.
template <class F>
double median_seconds(F&& run, int repeats, double min_sample) {
  using clock = std::chrono::steady_clock;
  auto time = [&](long n) {
    const auto start = clock::now();
    for (long i = 0; i < n; ++i) run();
    return std::chrono::duration<double>(clock::now() - start).count();
  };
  long n = 1;
  for (double s = time(1); s < min_sample && n < (1L << 20); s = time(n)) n *= 2;
  std::vector<double> samples;
  for (int r = 0; r < repeats; ++r) samples.push_back(time(n) / static_cast<double>(n));
  std::sort(samples.begin(), samples.end());
  return samples[samples.size() / 2];
}

/// One point, in the line format work_precision reads:
/// row,scene,stepper,control,tolerance,error,seconds_per_sim_second,rhs_evals,steps,rejected,jacobian_evals
inline void print_row(const std::string& scene, const std::string& stepper, const char* control, double tol,
                      double error, double sec_per_sim_s, long evals, long steps, long rejected) {
  std::printf("row,%s,%s,%s,%.6g,%.6g,%.6g,%ld,%ld,%ld,0\n", scene.c_str(), stepper.c_str(), control, tol, error,
              sec_per_sim_s, evals, steps, rejected);
  std::fflush(stdout);
}

struct options {
  std::string reference, scene;
  bool quick = false;
};

/// --quick is ctest's smoke run (benchmark.work_precision): a stepper's sweep
/// ends after a run of more than 20,000 evaluations, the next being ten times
/// that. Without it, Simbody's RungeKutta3 and Verlet at 1e-12 (about 380,000
/// and 340,000 realizations, timed three times) were 86 s of the test's 112.
inline bool quick_sweep_done(bool quick, long evals) { return quick && evals > 20000; }
inline bool parse(int argc, char** argv, options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") o.quick = true;
    else if (a == "--reference" && i + 1 < argc) o.reference = argv[++i];
    else if (a == "--scene" && i + 1 < argc) o.scene = argv[++i];
    else return false;
  }
  return !o.reference.empty();
}

}  // namespace peer
