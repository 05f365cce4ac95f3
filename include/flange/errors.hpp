// The exceptions flange throws. Every message names what went wrong, where, and
// with which value, so that a bad parameter or a numerical breakdown never
// shows up later as a silent NaN.
#pragma once
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
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
template <class... Args>
[[nodiscard]] std::string concat(const Args&... args) {
  std::ostringstream os;
  os.precision(17);
  (os << ... << args);
  return os.str();
}
/// A measured number for a message, to 6 digits (concat prints 17, which
/// a state needs and a depth or a size does not).
[[nodiscard]] inline std::string brief(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}
}  // namespace detail

}  // namespace flange
