// The ensemble recorders a Python module offers (python/module.hpp), chosen
// at run time: flange's C++ recorders (ensemble/record.hpp) over a state
// entry or the total energy, so that extrema, crossings and settling times
// come from every accepted step and the dense output, not from samples.
//
//   recorders={"swing": ("max_abs", "pivot.q", -pi/2),      # largest |q − about|
//              "top": ("max", "rail.q"), ("min", …), ("final", …),
//              "half": ("crossing", "pivot.v", 0.0, -1),     # first time it crosses a level (dir −1, 0, +1)
//              "settle": ("settling", "rail.q", 0.3, 0.01)}  # last time |q − about| > band
//
// "energy" names the total energy. A case's recorders sit in one fixed-size
// recorder (at most max_recorders columns), copied for every case without
// allocating.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <variant>

#include "flange/dynamics/energy.hpp"
#include "flange/ensemble/record.hpp"
#include "flange/errors.hpp"

namespace flange::python {

/// What a recorder watches: a state entry (or the total energy) less a
/// level, or the absolute value of that.
struct quantity {
  int index = -1;  ///< the state entry; −1 for the total energy
  double level = 0;
  bool absolute = false;
  template <class S, class X>
  double operator()(const S& s, double t, const X& x) const {
    double y = index >= 0 ? static_cast<double>(x[static_cast<std::size_t>(index)]) : energy(s, t, x).total();
    y -= level;
    return absolute ? std::abs(y) : y;
  }
};

/// One of the C++ recorders over a quantity, chosen at run time.
struct any_recorder {
  std::variant<std::monostate, ensemble::final_value_of<quantity>, ensemble::extremum_of<quantity, 1>,
               ensemble::extremum_of<quantity, -1>, ensemble::crossing_of<quantity>, ensemble::settling_of<quantity>>
      r;
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    std::visit([&](auto& a) {
      if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) a.start(s, t, x);
    }, r);
  }
  template <class V>
  void step(const V& v) {
    std::visit([&](auto& a) {
      if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) a.step(v);
    }, r);
  }
  template <class S, class X>
  void finish(const S& s, double t, const X& x, double* out) const {
    std::visit([&](const auto& a) {
      if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) a.finish(s, t, x, out);
    }, r);
  }
};

inline constexpr int max_recorders = 8;

/// Up to max_recorders recorders chosen at run time: max_recorders columns,
/// the unused ones NaN.
struct recorder_set {
  std::array<any_recorder, max_recorders> recs{};
  int n = 0;
  template <class S>
  static constexpr int width() {
    return max_recorders;
  }
  template <class S>
  void names(std::string*) const {}
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    for (int i = 0; i < n; ++i) recs[i].start(s, t, x);
  }
  template <class V>
  void step(const V& v) {
    for (int i = 0; i < n; ++i) recs[i].step(v);
  }
  template <class S, class X>
  void finish(const S& s, double t, const X& x, double* out) const {
    for (int i = 0; i < max_recorders; ++i) out[i] = ensemble::not_seen;
    for (int i = 0; i < n; ++i) recs[i].finish(s, t, x, out + i);
  }
};

/// A recorder from its kind and arguments (the Python tuple's, after the
/// quantity): throws parameter_error naming what is wrong.
inline any_recorder make_recorder(std::string_view kind, quantity q, const double* args, int n_args) {
  using namespace ensemble;
  const auto arg = [&](int i, double fallback) { return i < n_args ? args[i] : fallback; };
  const auto at_most = [&](int n) {
    if (n_args > n)
      throw parameter_error(flange::detail::concat("flange: recorder \"", kind, "\" takes ", n, " number(s) after the quantity, not ",
                                           n_args));
  };
  any_recorder a;
  if (kind == "final") {
    at_most(0);
    a.r = final_value_of<quantity>{{"", q}};
  } else if (kind == "max" || kind == "min") {
    at_most(0);
    if (kind == "max") a.r = extremum_of<quantity, 1>{{"", q}};
    else a.r = extremum_of<quantity, -1>{{"", q}};
  } else if (kind == "max_abs") {
    at_most(1);
    q.level = arg(0, 0.0);
    q.absolute = true;
    a.r = extremum_of<quantity, 1>{{"", q}};
  } else if (kind == "crossing") {
    at_most(2);
    q.level = arg(0, 0.0);
    const double dir = arg(1, 0.0);
    if (dir != -1 && dir != 0 && dir != 1)
      throw parameter_error(flange::detail::concat("flange: recorder \"crossing\": direction ", dir, " is not −1, 0 or +1"));
    a.r = crossing_of<quantity>{{"", q}, static_cast<int>(dir)};
  } else if (kind == "settling") {
    if (n_args != 2)
      throw parameter_error("flange: recorder \"settling\" takes the level it settles about and the band: "
                            "(\"settling\", quantity, about, band)");
    q.level = args[0];
    if (!(args[1] >= 0))
      throw parameter_error(flange::detail::concat("flange: recorder \"settling\": band ", args[1], " must be ≥ 0"));
    a.r = settling_of<quantity>{{"", q}, args[1]};
  } else {
    throw parameter_error(flange::detail::concat("flange: no recorder kind \"", kind,
                                         "\"; the kinds are final, max, min, max_abs, crossing, settling"));
  }
  return a;
}

}  // namespace flange::python
