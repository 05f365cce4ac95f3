// What an ensemble records per case: a fixed number of numbers (columns),
// from recorders that watch the integration step by step.
//
//   ensemble::final_state()                     the state at t1 (n_state columns)
//   ensemble::final_value("energy", f)          f at t1
//   ensemble::maximum("max_swing", f)           the largest f at the accepted steps
//   ensemble::minimum("min_gap", f)             the smallest
//   ensemble::crossing("half_period", f, +1)    the first time after t0 at which f crosses 0
//                                               upward (+1), downward (−1) or either (0),
//                                               found by bisection on the dense output
//   ensemble::settling_time("settle", f, band)  the last time |f| > band (0 if never)
//   ensemble::at_times<K>("s", f, {t₁, …, t_K})  f at chosen times (K columns)
//   ensemble::states_at(times, n, out)          the whole state at each of n times, into an
//                                               array of the caller's (no columns)
//
// f is called as f(scene, t, x) and returns a double. Names are string
// literals (a recorder is copied for every case and must not allocate). The
// values of a recorder that never saw its event (a crossing that did not
// happen) are NaN.
//
// A recorder is any type with
//   template <class S> static constexpr int width();       its number of columns
//   template <class S> void names(std::string* out) const;  its column names
//   void start(const S&, double t0, const X& x0);
//   void step(const V& s);       each accepted step: s.scene, s.t0, s.t1, s.x0, s.x1, s.at(t, x)
//                                (the integration loop's step_view, simulate/integrate.hpp: the
//                                ends after the projection, at(t, x) the interpolation, projected)
//   void finish(const S&, double t1, const X& x1, double* out);
// and, if it wants to know which case it records, void begin_case(std::size_t index);
// so users can write their own.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

namespace flange::ensemble {

inline constexpr double not_seen = std::numeric_limits<double>::quiet_NaN();

/// The state at t1.
struct final_state {
  template <class S>
  static constexpr int width() {
    return S::n_state;
  }
  template <class S>
  void names(std::string* out) const {
    // built as a number with a letter put in front, not "q" + std::to_string(i):
    // GCC 12 warns about the copy a string literal's assignment inlines
    // (-Wrestrict, a false positive)
    for (int i = 0; i < S::n_state; ++i) {
      std::string n = std::to_string(i < S::n_q ? i : i - S::n_q);
      n.insert(n.begin(), i < S::n_q ? 'q' : 'v');
      out[i] = std::move(n);
    }
  }
  template <class S, class X>
  void start(const S&, double, const X&) {}
  template <class V>
  void step(const V&) {}
  template <class S, class X>
  void finish(const S&, double, const X& x, double* out) const {
    for (int i = 0; i < S::n_state; ++i) out[i] = x[i];
  }
};

/// A recorder of one column with a name and a function f(scene, t, x).
template <class F>
struct named_function {
  std::string_view name;
  F f;
  template <class S>
  static constexpr int width() {
    return 1;
  }
  template <class S>
  void names(std::string* out) const {
    out[0] = std::string(name);
  }
};

template <class F>
struct final_value_of : named_function<F> {
  template <class S, class X>
  void start(const S&, double, const X&) {}
  template <class V>
  void step(const V&) {}
  template <class S, class X>
  void finish(const S& s, double t, const X& x, double* out) const {
    out[0] = this->f(s, t, x);
  }
};
template <class F>
final_value_of<F> final_value(std::string_view name, F f) {
  return {{name, f}};
}

template <class F, int Sign>
struct extremum_of : named_function<F> {
  double best = not_seen;
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    best = this->f(s, t, x);
  }
  template <class V>
  void step(const V& v) {
    const double y = this->f(v.scene, v.t1, v.x1);
    if (Sign * y > Sign * best || std::isnan(best)) best = y;
  }
  template <class S, class X>
  void finish(const S&, double, const X&, double* out) const {
    out[0] = best;
  }
};
/// The largest f over the start and the accepted steps' ends.
template <class F>
extremum_of<F, 1> maximum(std::string_view name, F f) {
  return {{name, f}};
}
/// The smallest f over the start and the accepted steps' ends.
template <class F>
extremum_of<F, -1> minimum(std::string_view name, F f) {
  return {{name, f}};
}

namespace detail {
/// The root of g on [a, b] where g(a) and g(b) differ in sign, by bisection
/// to the last bit of t.
template <class G>
double bisect(G&& g, double a, double b, double ga) {
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    const double gm = g(m);
    if ((gm > 0) == (ga > 0) && gm != 0) {
      a = m;
      ga = gm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}
}  // namespace detail

template <class F>
struct crossing_of : named_function<F> {
  int direction = 0;
  double last = not_seen, when = not_seen;
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    last = this->f(s, t, x);
    when = not_seen;
  }
  template <class V>
  void step(const V& v) {
    const double y = this->f(v.scene, v.t1, v.x1);
    if (std::isnan(when)) {
      const bool up = last < 0 && y >= 0, down = last > 0 && y <= 0;
      if ((direction >= 0 && up) || (direction <= 0 && down)) {
        auto x = v.x1;
        when = detail::bisect(
            [&](double t) {
              v.at(t, x);
              return this->f(v.scene, t, x);
            },
            v.t0, v.t1, last);
      }
    }
    last = y;
  }
  template <class S, class X>
  void finish(const S&, double, const X&, double* out) const {
    out[0] = when;
  }
};
/// The first time after t0 at which f crosses zero: upward (+1), downward
/// (−1) or either way (0). NaN if it never does.
template <class F>
crossing_of<F> crossing(std::string_view name, F f, int direction) {
  return {{name, f}, direction};
}

template <class F>
struct settling_of : named_function<F> {
  double band = 0;
  double last_out = 0, prev_abs = 0;
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    prev_abs = std::abs(this->f(s, t, x));
    last_out = prev_abs > band ? t : 0.0;
  }
  template <class V>
  void step(const V& v) {
    const double a = std::abs(this->f(v.scene, v.t1, v.x1));
    if (a > band) {
      last_out = v.t1;
    } else if (prev_abs > band) {
      // it came inside the band during this step: when, exactly
      auto x = v.x1;
      last_out = detail::bisect(
          [&](double t) {
            v.at(t, x);
            return std::abs(this->f(v.scene, t, x)) - band;
          },
          v.t0, v.t1, prev_abs - band);
    }
    prev_abs = a;
  }
  template <class S, class X>
  void finish(const S&, double, const X&, double* out) const {
    out[0] = last_out;
  }
};
/// The last time |f| > band (0 if |f| ≤ band throughout; t1 if it never
/// settles): the settling time into the band.
template <class F>
settling_of<F> settling_time(std::string_view name, F f, double band) {
  return {{name, f}, band};
}

template <int K, class F>
struct at_times_of {
  std::string_view name;
  F f;
  std::array<double, K> times;
  std::array<double, K> values{};
  template <class S>
  static constexpr int width() {
    return K;
  }
  template <class S>
  void names(std::string* out) const {
    for (int k = 0; k < K; ++k) out[k] = std::string(name) + "@" + std::to_string(times[k]);
  }
  template <class S, class X>
  void start(const S& s, double t, const X& x) {
    for (int k = 0; k < K; ++k) values[k] = times[k] == t ? f(s, t, x) : not_seen;
  }
  template <class V>
  void step(const V& v) {
    for (int k = 0; k < K; ++k)
      if (times[k] > v.t0 && times[k] <= v.t1) {
        auto x = v.x1;
        if (times[k] < v.t1) v.at(times[k], x);
        values[k] = f(v.scene, times[k], x);
      }
  }
  template <class S, class X>
  void finish(const S&, double, const X&, double* out) const {
    for (int k = 0; k < K; ++k) out[k] = values[k];
  }
};
/// f at chosen times (within [t0, t1]), from the dense output: a sampled
/// trajectory of one output.
template <int K, class F>
at_times_of<K, F> at_times(std::string_view name, F f, std::array<double, K> times) {
  return {name, f, times};
}

/// The whole state at each of n times (times[0] = t0, increasing, the last
/// t1), written into the caller's array: case i's state at times[k] at
/// out + (i·n + k)·n_state. The states are those simulate(scene, x0, times)
/// returns, bit for bit: the same dense output inside the same steps. It has
/// no columns; a failed case's rows after its failure keep what the array
/// held (fill it with NaN first to tell). Each case writes only its own
/// rows, so parallel policies need no lock.
class states_at {
 public:
  states_at(const double* times, std::size_t n, double* out) : times_(times), n_(n), out_(out) {}
  template <class S>
  static constexpr int width() {
    return 0;
  }
  template <class S>
  void names(std::string*) const {}
  void begin_case(std::size_t index) { index_ = index; }
  template <class S, class X>
  void start(const S&, double, const X& x0) {
    width_ = S::n_state;
    row_ = out_ + index_ * n_ * width_;
    put(0, x0);
    next_ = 1;
  }
  template <class V>
  void step(const V& v) {
    for (; next_ < n_ && v.t1 - times_[next_] >= 0; ++next_) {
      auto x = v.x1;
      if (times_[next_] != v.t1) v.at(times_[next_], x);
      put(next_, x);
    }
  }
  /// The last step ends on t1 to round-off: a time it stopped a few ulp
  /// short of is the end state's (as simulate does).
  template <class S, class X>
  void finish(const S&, double, const X& x1, double*) {
    for (; next_ < n_; ++next_) put(next_, x1);
  }

 private:
  const double* times_;
  std::size_t n_;
  double* out_;
  std::size_t index_ = 0, width_ = 0, next_ = 0;
  double* row_ = nullptr;  ///< this case's first row
  template <class X>
  void put(std::size_t k, const X& x) {
    for (std::size_t i = 0; i < width_; ++i) row_[k * width_ + i] = static_cast<double>(x[i]);
  }
};

}  // namespace flange::ensemble
