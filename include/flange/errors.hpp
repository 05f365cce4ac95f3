// The exceptions flange throws. Every message names what went wrong, where, and
// with which value, so that a bad parameter or a numerical breakdown never
// shows up later as a silent NaN.
#pragma once
#include <charconv>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace flange {

/// Base of every flange exception.
struct error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A parameter that no physical scene can have (negative mass, zero axis, NaN…),
/// thrown at construction. The message names the component and the value.
struct parameter_error : error {
  using error::error;
};

/// A breakdown during simulation (singular mass matrix, non-finite state,
/// stepper failure). The message gives the time, the state and the reason;
/// the members give them as values (the state and reason empty where the
/// thrower had none to give).
struct simulation_error : error {
  simulation_error(const std::string& what, double t, std::vector<double> x = {}, std::string why = {})
      : error(what), time(t), state(std::move(x)), reason(std::move(why)) {}
  double time;
  std::vector<double> state;  ///< the state at `time`
  std::string reason;         ///< what went wrong, without the time and the state
};

namespace detail {
/// Appends x as printf("%.*g", digits, x) writes it (what an ostream at that
/// precision writes), without a stream. The pieces of a message are out
/// of line: a message is written once, when something has gone wrong, and
/// each call site should cost the compiler a call, not a copy of to_chars.
[[gnu::noinline, gnu::cold]] inline void append_number(std::string& out, double x, int digits = 17) {
  char buf[48];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, digits);
  out.append(buf, r.ptr);
}
[[gnu::noinline, gnu::cold]] inline void append_number(std::string& out, long double x, int digits = 17) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, digits);
  out.append(buf, r.ptr);
}

// One piece of a message: text, a character, a number, or a fixed-size
// matrix (Eigen's, or anything with rows(), cols() and (i, j)) written as
// "a b c" for a vector and "a b c; d e f; g h i" row by row for a matrix.
[[gnu::noinline, gnu::cold]] inline void append_piece(std::string& out, std::string_view s) { out += s; }
[[gnu::noinline, gnu::cold]] inline void append_piece(std::string& out, char c) { out += c; }
inline void append_piece(std::string& out, double x) { append_number(out, x); }
inline void append_piece(std::string& out, float x) { append_number(out, static_cast<double>(x)); }
inline void append_piece(std::string& out, long double x) { append_number(out, x); }
template <class I>
  requires std::is_integral_v<I>
[[gnu::noinline, gnu::cold]] void append_piece(std::string& out, I i) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, i);
  out.append(buf, r.ptr);
}
template <class M>
  requires requires(const M& m) {
    m.rows();
    m.cols();
    m.eval();
  }
[[gnu::noinline, gnu::cold]] void append_piece(std::string& out, const M& m) {
  const auto e = m.eval();
  const bool vector = e.rows() == 1 || e.cols() == 1;
  for (int i = 0; i < int(e.rows()); ++i)
    for (int j = 0; j < int(e.cols()); ++j) {
      if (i + j > 0) out += vector || j > 0 ? " " : "; ";
      append_number(out, static_cast<double>(e(i, j)));
    }
}

/// The message made of args, numbers to 17 significant digits.
template <class... Args>
[[nodiscard]] std::string concat(const Args&... args) {
  std::string out;
  (append_piece(out, args), ...);
  return out;
}
/// A measured number for a message, to 6 digits (concat prints 17, which
/// a state needs and a depth or a size does not).
[[nodiscard]] inline std::string brief(double x) {
  std::string out;
  append_number(out, x, 6);
  return out;
}
}  // namespace detail

}  // namespace flange
