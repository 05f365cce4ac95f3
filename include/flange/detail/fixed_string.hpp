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
  constexpr fixed_string() = default;
  constexpr fixed_string(const char (&s)[N]) { std::copy_n(s, N, data); }
  /// From a constant string of length N − 1 (a name held in a constexpr table).
  constexpr explicit fixed_string(std::string_view s) { std::copy_n(s.data(), N - 1, data); }
  [[nodiscard]] constexpr std::string_view view() const { return {data, N - 1}; }
  [[nodiscard]] constexpr std::size_t size() const { return N - 1; }
};

/// A name as a type, for diagnostics: the compiler prints member<"elbw">.
namespace diagnostic {
template <fixed_string Name>
struct member {};
}  // namespace diagnostic

/// a + b, at compile time ("j3" + ".frame_b").
template <std::size_t A, std::size_t B>
constexpr fixed_string<A + B - 1> operator+(const fixed_string<A>& a, const fixed_string<B>& b) {
  fixed_string<A + B - 1> r;
  std::copy_n(a.data, A - 1, r.data);
  std::copy_n(b.data, B, r.data + A - 1);
  return r;
}

template <std::size_t A, std::size_t B>
constexpr fixed_string<A + B - 1> operator+(const fixed_string<A>& a, const char (&b)[B]) {
  return a + fixed_string<B>(b);
}

/// The number of decimal digits of I ≥ 0.
constexpr std::size_t decimal_digits(int i) {
  std::size_t n = 1;
  for (; i >= 10; i /= 10) ++n;
  return n;
}

/// A name with a number: indexed_name<"link", 3>() == "link3" (I ≥ 0).
template <fixed_string Prefix, int I>
constexpr auto indexed_name() {
  static_assert(I >= 0, "flange: indexed names take a number from 0 up");
  constexpr std::size_t n = decimal_digits(I);
  char digits[n + 1] = {};
  int i = I;
  for (std::size_t k = n; k-- > 0; i /= 10) digits[k] = char('0' + i % 10);
  return Prefix + fixed_string<n + 1>(digits);
}

}  // namespace flange
