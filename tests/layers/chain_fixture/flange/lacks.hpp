#pragma once
#include "flange/base.hpp"
// Names std::unordered_map without including <unordered_map>: not
// self-contained, although top.hpp, which includes it, compiles alone.
inline std::unordered_map<int, int> lacks() { return {}; }
