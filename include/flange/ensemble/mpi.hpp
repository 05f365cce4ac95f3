// Ensembles across machines, with Boost.MPI over Open MPI (Debian's
// libboost-mpi-dev and openmpi-bin): the same program runs on a laptop and,
// under mpirun, on a cluster.
//
//   boost::mpi::environment env(argc, argv);
//   boost::mpi::communicator world;
//   auto res = flange::ensemble::run_mpi(world, study, cases, flange::ensemble::tbb_threads{});
//   if (world.rank() == 0) res.write_csv(file, cases);
//
// Distribution: static and cyclic. Rank r of P runs cases r, r + P, r + 2P, …
// (with its local policy: serial, or TBB threads inside the rank), then the
// rows are gathered to rank 0 in one collective and put back in case order.
// Cyclic, not contiguous blocks, because a sweep's cost usually varies
// smoothly along its grid (stiffer gains, heavier loads): interleaving gives
// every rank a sample of the whole range, so uneven costs even out without a
// master rank that hands out work and sits idle, and without a message per
// case. The one message per rank is the gather (about 8·(n_outputs + n_state
// + 4) bytes per case, plus failure reasons).
//
// For sweeps too large for rank 0's memory, stream_mpi hands each rank's
// blocks to a sink of its own (write one CSV per rank; concatenate and sort
// by the case column).
//
// Results equal a serial run of the same cases bit for bit: each case is
// computed by the same code from the same inputs, wherever it runs.
//
// Link Boost::mpi and Boost::serialization (or this build's flange::mpi).
#pragma once
#include <string>
#include <vector>

#include <boost/mpi/collectives/gather.hpp>
#include <boost/mpi/communicator.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include "flange/ensemble/ensemble.hpp"

namespace flange::ensemble {

/// Rank `comm.rank()`'s share of the cases (r, r + P, …), each block handed
/// to sink(first, last) in case order within the rank.
template <class Study, int K, class Policy, class Sink>
void stream_mpi(const boost::mpi::communicator& comm, const Study& study, const case_set<K>& cases,
                const Policy& local, Sink&& sink, run_options opt = {}) {
  if (comm.rank() != 0) opt.progress_line = run_options::show::never;
  study.stream(cases, local, sink, opt, static_cast<std::size_t>(comm.rank()), static_cast<std::size_t>(comm.size()));
}

/// Every case's row on rank 0, in case order (the other ranks get no rows).
template <class Study, int K, class Policy = serial>
auto run_mpi(const boost::mpi::communicator& comm, const Study& study, const case_set<K>& cases,
             const Policy& local = {}, run_options opt = {}) {
  using R = typename Study::template results_type<K>;
  using O = typename Study::template outcome_type<K>;
  constexpr int NOut = Study::template n_outputs<K>;
  constexpr int NState = static_cast<int>(std::tuple_size_v<decltype(O::fail_state)>);
  // This rank's rows, flattened into what Boost.MPI serialises cheaply.
  std::vector<double> reals;
  std::vector<long> ints;
  std::vector<std::string> reasons;
  stream_mpi(comm, study, cases, local,
             [&](auto first, auto last) {
               for (auto it = first; it != last; ++it) {
                 ints.insert(ints.end(), {static_cast<long>(it->index), it->ok ? 1L : 0L, it->rhs_evals, it->steps});
                 reals.insert(reals.end(), it->values.begin(), it->values.end());
                 reals.push_back(it->fail_time);
                 reals.insert(reals.end(), it->fail_state.begin(), it->fail_state.end());
                 reasons.push_back(it->reason);
               }
             },
             opt);
  std::vector<std::vector<double>> all_reals;
  std::vector<std::vector<long>> all_ints;
  std::vector<std::vector<std::string>> all_reasons;
  boost::mpi::gather(comm, reals, all_reals, 0);
  boost::mpi::gather(comm, ints, all_ints, 0);
  boost::mpi::gather(comm, reasons, all_reasons, 0);
  R res{study.template outputs<K>(), {}};
  if (comm.rank() != 0) return res;
  res.rows.resize(cases.size());
  for (std::size_t r = 0; r < all_ints.size(); ++r) {
    const std::size_t n = all_reasons[r].size();
    for (std::size_t i = 0; i < n; ++i) {
      O o;
      o.index = static_cast<std::size_t>(all_ints[r][4 * i]);
      o.ok = all_ints[r][4 * i + 1] != 0;
      o.rhs_evals = all_ints[r][4 * i + 2];
      o.steps = all_ints[r][4 * i + 3];
      const double* v = all_reals[r].data() + i * (NOut + 1 + NState);
      for (int k = 0; k < NOut; ++k) o.values[k] = v[k];
      o.fail_time = v[NOut];
      for (int k = 0; k < NState; ++k) o.fail_state[k] = v[NOut + 1 + k];
      o.reason = std::move(all_reasons[r][i]);
      res.rows[o.index] = std::move(o);
    }
  }
  return res;
}

}  // namespace flange::ensemble
