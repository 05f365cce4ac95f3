// libFuzzer target: bytes → parameters and a state for one of eight
// compile-time scene shapes (spatial and planar trees of every joint kind
// and force element, a spatial chain on run-time axes, the paper's crane, a
// four-bar, a slider-crank, shapes in contact and a quadruped on its feet),
// then the derivative, a short checked
// simulation and recovery, with the invariants of fuzz/scenes_fuzz.hpp. The
// first byte picks the scene, the second whether its numbers are tame or
// wild. docs/fuzzing.md says how to build and run it.
#include "scenes_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace flange::fuzz;
  if (size < 2) return 0;
  bytes b{data + 2, size - 2, (data[1] & 1) != 0};
  try {
    switch (const int k = data[0] % 8; k / 2) {
      case 0: fuzz_trees(b, k % 2); break;
      case 1: fuzz_chain_and_crane(b, k % 2); break;
      case 2: fuzz_loops(b, k % 2); break;
      default: fuzz_contacts(b, k % 2);
    }
  } catch (const flange::error& e) {
    finding("a flange::error escaped where none was expected:", e.what());
  } catch (const std::exception& e) {
    finding("an exception that is not a flange::error:", e.what());
  }
  return 0;
}
