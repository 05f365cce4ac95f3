// Ensemble throughput: cases per second for the paper's arm and the
// controlled crane, serially, with oneTBB threads, and over MPI ranks, with
// the parallel efficiency against the serial run measured in the same run.
//
//   build/benchmarks/ensemble_throughput                       serial and TBB (2 threads)
//   mpirun -np 2 build/benchmarks/ensemble_throughput --mpi    serial and 2 MPI ranks (serial in each)
//
// One line per measurement, exactly:
//   ensemble <scene> engine=<serial|tbb<n>|mpi<n>> cases=<n> case_us=<µs per case, serial> cases_per_s=<x> efficiency=<x / (n · serial)>
// Times are medians of 5 runs of the whole ensemble.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <vector>

#include <flange/ensemble/ensemble.hpp>
#include <flange/models/controlled_crane.hpp>
#include <flange/models/paper.hpp>
#ifdef FLANGE_ENSEMBLE_TBB
#include <flange/ensemble/tbb.hpp>
#endif
#ifdef FLANGE_ENSEMBLE_MPI
#include <boost/mpi/collectives/broadcast.hpp>
#include <boost/mpi/environment.hpp>
#include <flange/ensemble/mpi.hpp>
#endif

using namespace flange;
namespace en = flange::ensemble;

namespace {

template <class F>
double median_seconds(F&& f, int repeats = 5) {
  f();  // warm-up: thread pools start, caches fill
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto s = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void line(const char* scene, const char* engine, std::size_t n, double serial_s, double s, int workers) {
  const double rate = n / s, serial_rate = n / serial_s;
  std::printf("ensemble %s engine=%s cases=%zu case_us=%.1f cases_per_s=%.1f efficiency=%.2f\n", scene, engine, n,
              1e6 * serial_s / n, rate, rate / (workers * serial_rate));
  std::fflush(stdout);
}

const en::run_options quiet{.block = 256, .progress_line = en::run_options::show::never};

/// The paper's arm released from 1000 amplitudes, 20 s each at 1e-10.
auto arm_study() {
  auto setup = [](const std::array<double, 1>& c) {
    return std::pair{models::robot_arm(), decltype(models::robot_arm())::state_type{c[0], 0.0}};
  };
  return en::make(setup, 0.0, 20.0, {.tolerance = 1e-10},
                  en::maximum("max_rate", [](const auto&, double, const auto& x) { return std::abs(x[1]); }),
                  en::final_state{});
}
const auto arm_cases = en::grid<1>({"phi0"}, {en::linspace(-3.0, 0.0, 1000)});

/// The controlled crane over 20 × 20 gains and loads, 20 s each at 1e-8.
auto crane_study() {
  auto setup = [](const std::array<double, 2>& c) {
    models::controlled_crane_params p;
    p.m_load = c[1];
    p.buffer_c = 5.0;
    p.controller = {.kp = c[0], .kd = 2 * 0.7 * std::sqrt(c[0] * (p.m_cart + c[1])), .target = 1.0};
    return std::pair{models::controlled_crane(p), models::controlled_crane_rest()};
  };
  auto swing = [](const auto&, double, const auto& x) { return std::abs(x[1] + std::numbers::pi / 2); };
  return en::make(setup, 0.0, 20.0, {.tolerance = 1e-8},
                  en::maximum("max_swing", swing), en::settling_time("settle", swing, 0.01));
}
const auto crane_cases = en::grid<2>({"kp", "m_load"}, {en::logspace(2, 200, 20), en::linspace(0.1, 3.0, 20)});

template <class Study, int K>
void local(const char* name, const Study& study, const en::case_set<K>& cases) {
  const double serial = median_seconds([&] { study.run(cases, en::serial{}, quiet); });
  line(name, "serial", cases.size(), serial, serial, 1);
#ifdef FLANGE_ENSEMBLE_TBB
  const en::tbb_threads two{2};
  const double tbb = median_seconds([&] { study.run(cases, two, quiet); });
  line(name, "tbb2", cases.size(), serial, tbb, 2);
#endif
}

#ifdef FLANGE_ENSEMBLE_MPI
template <class Study, int K>
void over_ranks(const boost::mpi::communicator& world, const char* name, const Study& study,
                const en::case_set<K>& cases) {
  double serial = 0;
  if (world.rank() == 0) serial = median_seconds([&] { study.run(cases, en::serial{}, quiet); });
  boost::mpi::broadcast(world, serial, 0);
  std::vector<double> t;
  for (int r = 0; r < 6; ++r) {  // the first is a warm-up
    world.barrier();
    const auto s = std::chrono::steady_clock::now();
    en::run_mpi(world, study, cases, en::serial{}, quiet);
    world.barrier();
    if (r > 0) t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
  }
  std::sort(t.begin(), t.end());
  if (world.rank() == 0) {
    line(name, "serial", cases.size(), serial, serial, 1);
    char engine[32];
    std::snprintf(engine, sizeof engine, "mpi%d", world.size());
    line(name, engine, cases.size(), serial, t[2], world.size());
  }
}
#endif

}  // namespace

int main(int argc, char** argv) {
  const bool mpi = argc > 1 && !std::strcmp(argv[1], "--mpi");
  if (argc > 2 || (argc == 2 && !mpi)) {
    std::fprintf(stderr, "usage: ensemble_throughput [--mpi]   (--mpi under mpirun -np N)\n");
    return 2;
  }
  if (!mpi) {
    local("robot_arm", arm_study(), arm_cases);
    local("controlled_crane", crane_study(), crane_cases);
    return 0;
  }
#ifdef FLANGE_ENSEMBLE_MPI
  boost::mpi::environment env(argc, argv);
  boost::mpi::communicator world;
  over_ranks(world, "robot_arm", arm_study(), arm_cases);
  over_ranks(world, "controlled_crane", crane_study(), crane_cases);
  return 0;
#else
  std::fprintf(stderr, "ensemble_throughput: built without Boost.MPI (tools/install-deps.sh --ensembles)\n");
  return 2;
#endif
}
