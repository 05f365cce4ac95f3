// Ensembles over MPI ranks (flange/ensemble/mpi.hpp), run by ctest as
//   mpirun --oversubscribe -np 2 ensemble_mpi_test
// Rank 0 compares the gathered rows with a serial run of the same cases, bit
// for bit: cyclic distribution, TBB inside the ranks, and a failing case;
// and a four-bar's cases over the ranks with simulate() of each case, bit
// for bit, their loop closed to 1e-10 after 50 s at tolerance 1e-6.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include <boost/mpi/environment.hpp>

#include <flange/ensemble/mpi.hpp>
#include <flange/ensemble/tbb.hpp>
#include <flange/flange.hpp>
#include <flange/models/controlled_crane.hpp>

#include "invariant_scenes.hpp"

using namespace flange;
namespace en = flange::ensemble;

int main(int argc, char** argv) {
  boost::mpi::environment env(argc, argv);
  boost::mpi::communicator world;
  auto cases = en::sample<2>({"kp", "m_load"}, {en::log_uniform(1, 100), en::uniform(0.05, 3.0)}, 41, 2024);
  cases.cases[5][1] = -1.0;  // a case that fails (negative mass), on rank 1
  auto setup = [](const std::array<double, 2>& c) {
    models::controlled_crane_params p;
    p.m_load = c[1];
    p.controller = {.kp = c[0], .kd = 2 * 0.7 * std::sqrt(c[0] * (p.m_cart + c[1])), .target = 1.0};
    return std::pair{models::controlled_crane(p), models::controlled_crane_rest()};
  };
  auto swing = [](const auto&, double, const auto& x) { return std::abs(x[1] + std::numbers::pi / 2); };
  auto study = en::make(setup, 0.0, 4.0, {.tolerance = 1e-8},
                        en::maximum("max_swing", swing), en::settling_time("settle", swing, 0.01), en::final_state{});
  const en::run_options quiet{.block = 8, .progress_line = en::run_options::show::never};
  const auto by_ranks = en::run_mpi(world, study, cases, en::serial{}, quiet);
  const auto by_ranks_tbb = en::run_mpi(world, study, cases, en::tbb_threads{1}, quiet);
  // A loop scene over the ranks: three crank speeds.
  const auto speeds = en::list<1>({"crank_rate"}, {{3.0}, {6.0}, {9.0}});
  auto fourbar_at = [](const std::array<double, 1>& c) {
    auto fb = invariant_scenes::fourbar();
    auto x = invariant_scenes::fourbar_start(fb);
    x[3] = c[0];
    close_loops<"crank_pivot">(fb, x);
    return std::pair{fb, x};
  };
  auto loop_study = en::make(fourbar_at, 0.0, 50.0, {.tolerance = 1e-6},
                             en::final_state{});
  const auto loops_by_ranks = en::run_mpi(world, loop_study, speeds, en::serial{}, quiet);
  if (world.rank() != 0) return 0;
  int loop_bad = 0;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    const auto& row = loops_by_ranks.rows[i];
    auto [fb, x0] = fourbar_at(speeds[i]);
    const auto x = simulate(fb, x0, 0.0, 50.0, {.tolerance = 1e-6});
    const auto r = loop_residual(fb, x);
    if (!row.ok || std::memcmp(row.values.data(), x.data(), sizeof x) != 0 || r.max_phi() > 1e-10 ||
        r.max_phid() > 1e-10) {
      std::printf("four-bar case %zu: ok %d, |Φ| = %g, |G·v| = %g, %s simulate()\n", i, int(row.ok), r.max_phi(),
                  r.max_phid(), std::memcmp(row.values.data(), x.data(), sizeof x) ? "differs from" : "equals");
      ++loop_bad;
    }
  }
  std::printf("four-bar over %d ranks: %zu cases, %s\n", world.size(), speeds.size(),
              loop_bad ? "MISMATCH" : "closed and identical to simulate() bit for bit");
  const auto serial = study.run(cases, en::serial{}, quiet);
  int bad = 0;
  auto compare = [&](const auto& a, const char* what) {
    if (a.rows.size() != serial.rows.size()) {
      std::printf("%s: %zu rows, serial %zu\n", what, a.rows.size(), serial.rows.size());
      ++bad;
      return;
    }
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
      const auto &x = a.rows[i], &y = serial.rows[i];
      bool same = x.index == i && x.ok == y.ok && x.rhs_evals == y.rhs_evals && x.steps == y.steps &&
                  x.reason == y.reason && std::memcmp(x.values.data(), y.values.data(), sizeof x.values) == 0 &&
                  std::memcmp(x.fail_state.data(), y.fail_state.data(), sizeof x.fail_state) == 0;
      if (!same) {
        std::printf("%s: case %zu differs from the serial run\n", what, i);
        ++bad;
      }
    }
  };
  compare(by_ranks, "mpi");
  compare(by_ranks_tbb, "mpi + tbb");
  if (serial.failed() != 1 || serial.rows[5].ok) {
    std::printf("expected exactly case 5 to fail, %zu failed\n", serial.failed());
    ++bad;
  }
  std::printf("ensemble over %d ranks: %zu cases, %zu failed as expected, %s\n", world.size(), serial.rows.size(),
              serial.failed(), bad ? "MISMATCH" : "identical to the serial run bit for bit");
  return bad || loop_bad ? 1 : 0;
}
