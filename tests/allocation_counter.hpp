// How many heap allocations the program has made so far
// (allocation_counter.cpp, linked with -Wl,--wrap=malloc,… in CMakeLists.txt).
#pragma once

namespace flange::test {
long allocations_so_far();

/// How many allocations f makes.
template <class F>
long count_allocations(F&& f) {
  const long before = allocations_so_far();
  f();
  return allocations_so_far() - before;
}
}  // namespace flange::test
