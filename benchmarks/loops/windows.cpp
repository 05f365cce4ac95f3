// One size of the loops benchmark's window row (loops.hpp): LOOPS_WINDOWS
// windows, set by benchmarks/CMakeLists.txt.
#include "loops.hpp"

namespace {
const bool added = (loops::cases().push_back({LOOPS_WINDOWS, &loops::window_row_case<LOOPS_WINDOWS>}), true);
}
