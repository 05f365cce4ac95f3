// The valid name closest to a mistyped one, at compile time, for "did you
// mean" in diagnostics: the least edit distance (insertions, deletions,
// substitutions and swaps of neighbours), the first in table order on a tie.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <string_view>

namespace flange::detail {

/// The Greek letters of variable names and how they are typed in ASCII
/// ("phi" for φ, "w" for ω), so that internal<"joint", "phi"> finds φ.
struct ascii_letter {
  std::string_view utf8, ascii;
};
inline constexpr std::array<ascii_letter, 4> ascii_letters{
    {{"\u03c6", "phi"}, {"\u03c9", "w"}, {"\u03c4", "tau"}, {"\u03bb", "lambda"}}};

/// A name with its Greek letters spelt in ASCII (up to 63 characters).
struct ascii_name {
  char data[64]{};
  std::size_t size = 0;
  constexpr ascii_name() = default;
  constexpr explicit ascii_name(std::string_view s) {
    for (std::size_t i = 0; i < s.size();) {
      bool done = false;
      for (const auto& l : ascii_letters)
        if (!done && s.substr(i, l.utf8.size()) == l.utf8) {
          for (char c : l.ascii) put(c);
          i += l.utf8.size();
          done = true;
        }
      if (!done) put(s[i++]);
    }
  }
  constexpr void put(char c) {
    if (size < sizeof data - 1) data[size++] = c;
  }
  [[nodiscard]] constexpr std::string_view view() const { return {data, size}; }
};
/// Does a name given by the user mean the declared one (as written, or with
/// its Greek letters in ASCII)?
constexpr bool same_name(std::string_view declared, std::string_view given) {
  return declared == given || ascii_name(declared).view() == given;
}

/// Optimal-string-alignment distance between a and b (names up to 127 characters).
constexpr int edit_distance(std::string_view a, std::string_view b) {
  constexpr std::size_t cap = 128;
  if (a.size() >= cap || b.size() >= cap) return int(std::max(a.size(), b.size()));
  std::array<std::array<int, cap>, 3> row{};  // rows i − 2, i − 1, i
  for (std::size_t j = 0; j <= b.size(); ++j) row[1][j] = int(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    auto& cur = row[(i + 1) % 3];
    const auto& prev = row[i % 3];
    const auto& prev2 = row[(i + 2) % 3];
    cur[0] = int(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      int d = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d = std::min(d, prev2[j - 2] + 1);
      cur[j] = d;
    }
  }
  return row[(a.size() + 1) % 3][b.size()];
}

/// The index in names (any range of names: an array, a vector of strings)
/// of the one closest to name (−1 if names is empty).
template <class Names>
constexpr int closest_name(std::string_view name, const Names& names) {
  int best = -1, best_d = 0, i = 0;
  for (const auto& n : names) {
    const int d = edit_distance(name, std::string_view(n));
    if (best < 0 || d < best_d) best = i, best_d = d;
    ++i;
  }
  return best;
}

}  // namespace flange::detail
