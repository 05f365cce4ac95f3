// A string usable as a template argument, so that component names are part of
// a scene's type: Revolute<"joint"> and Revolute<"elbow"> are different types,
// and the compiler's diagnostics print the name.
#pragma once
#include <algorithm>
#include <cstddef>
#include <string_view>

namespace flange {

template <std::size_t N>
struct fixed_string {
  char data[N]{};
  constexpr fixed_string(const char (&s)[N]) { std::copy_n(s, N, data); }
  [[nodiscard]] constexpr std::string_view view() const { return {data, N - 1}; }
  [[nodiscard]] constexpr std::size_t size() const { return N - 1; }
};

}  // namespace flange
