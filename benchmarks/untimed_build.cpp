// Linked, through flange_bench_common, into every benchmark program of a build configured with
// -DFLANGE_BENCHMARK_TIMING=OFF (benchmarks/CMakeLists.txt): such a build
// checks that the benchmarks run and print their lines, and its times are
// not the library's, which this says before the program prints anything.
#include <cstdio>

namespace {
[[maybe_unused]] const bool untimed_notice = [] {
  std::fputs(
      "flange benchmark: built with -DFLANGE_BENCHMARK_TIMING=OFF (steps not forced inline, as the unit tests "
      "build): the lines are checked, the times are not flange's; configure with -DFLANGE_BENCHMARK_TIMING=ON "
      "to time\n",
      stderr);
  return true;
}();
}  // namespace
