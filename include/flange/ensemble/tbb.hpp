// Ensembles on every core of one machine, with oneTBB (Debian's libtbb-dev).
//
//   auto res = study.run(cases, flange::ensemble::tbb_threads{});    // all cores
//   auto res = study.run(cases, flange::ensemble::tbb_threads{2});   // two threads
//
// Cases of a block are spread over TBB's workers (parallel_for in a
// task_arena of the chosen size); each case runs on one worker's stack, so a
// worker reuses nothing but its stack and allocates nothing per step. Rows come
// back in case order: the block's rows are written by case index and handed
// on when the block is done, so the results are those of a serial run, bit
// for bit, whatever the number of threads.
//
// Link TBB::tbb (CMake: find_package(TBB) and target_link_libraries(app
// PRIVATE TBB::tbb), or the flange::tbb target of this project's build).
#pragma once
#include <cstddef>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "flange/ensemble/ensemble.hpp"

namespace flange::ensemble {

/// Runs a block's cases in parallel on `threads` TBB threads (0: as many as
/// the machine has cores). The arena is made with the policy and shared by
/// its copies; TBB starts its threads at the first block (task_arena
/// initialises itself once, safely, even when two threads run studies with
/// one policy at the same time).
struct tbb_threads {
  int threads = 0;
  tbb_threads(int n = 0)  // NOLINT: tbb_threads{2} reads as "two threads"
      : threads(n), arena_(std::make_shared<tbb::task_arena>(n > 0 ? n : int(tbb::task_arena::automatic))) {}
  template <class F>
  void for_each(std::size_t n, F&& f) const {
    arena_->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
      });
    });
  }

 private:
  std::shared_ptr<tbb::task_arena> arena_;
};

}  // namespace flange::ensemble
