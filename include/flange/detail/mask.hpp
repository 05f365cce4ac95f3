// The positions where a mask known at compile time is true, in order: what
// a scene's arguments that are components or connections are
// (scene/scene.hpp), and the rates a cut's rows can touch
// (dynamics/loop_solve.hpp). Counted by a loop, not a fold: clang nests a
// fold's terms, 256 deep at most, and a scene can have more arguments.
#pragma once
#include <array>

namespace flange::detail {

/// The indices where Mask (a std::array<bool, N>) is true, in order.
template <auto Mask>
constexpr auto indices_of() {
  constexpr int n = [] {
    int c = 0;
    for (bool b : Mask) c += b;
    return c;
  }();
  std::array<int, n> r{};
  int c = 0;
  for (int i = 0; i < int(Mask.size()); ++i)
    if (Mask[i]) r[c++] = i;
  return r;
}

}  // namespace flange::detail
