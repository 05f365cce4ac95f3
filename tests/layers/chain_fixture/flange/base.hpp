#pragma once
#include <vector>
inline std::vector<int> base() { return {}; }
