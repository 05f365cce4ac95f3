#pragma once
#include <unordered_map>
#include "flange/lacks.hpp"
inline int top() { return static_cast<int>(lacks().size() + base().size()); }
