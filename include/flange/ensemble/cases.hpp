// The cases of an ensemble: K named run-time parameters per case, given as a
// grid, a list, or seeded samples from distributions.
//
//   auto c = ensemble::grid<2>({"kp", "m_load"}, {ensemble::linspace(2, 40, 20), ensemble::linspace(0.1, 2, 20)});
//   auto s = ensemble::sample<2>({"m", "d"}, {ensemble::normal(1.0, 0.05), ensemble::uniform(0.4, 0.6)}, 10000, 42);
//
// Case i is row i of every output, whatever runs it (serially, on threads, on
// MPI ranks). Samples come from std::mt19937_64, whose sequence the C++
// standard fixes, turned into numbers by explicit formulas (no
// implementation-defined std:: distributions), so a seed gives the same cases
// on every rank and every run.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "flange/errors.hpp"

namespace flange::ensemble {

/// K named parameters per case, the cases in order.
template <int K>
struct case_set {
  using case_type = std::array<double, K>;
  static constexpr int n_parameters = K;
  std::array<std::string, K> names;
  std::vector<case_type> cases;

  [[nodiscard]] std::size_t size() const { return cases.size(); }
  const case_type& operator[](std::size_t i) const { return cases[i]; }
};

/// n values from a to b, evenly spaced, both ends included.
inline std::vector<double> linspace(double a, double b, int n) {
  if (n < 1) throw parameter_error(::flange::detail::concat("ensemble::linspace: n = ", n, ", needs at least 1 value"));
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = n == 1 ? a : a + (b - a) * i / (n - 1);
  return v;
}

/// n values from a to b (both > 0), evenly spaced in log.
inline std::vector<double> logspace(double a, double b, int n) {
  if (!(a > 0 && b > 0)) throw parameter_error(::flange::detail::concat("ensemble::logspace: ends ", a, ", ", b, " must be > 0"));
  auto v = linspace(std::log(a), std::log(b), n);
  for (auto& x : v) x = std::exp(x);
  return v;
}

/// The Cartesian product of K named axes; the last parameter varies fastest.
template <int K>
case_set<K> grid(std::array<std::string, K> names, const std::array<std::vector<double>, K>& axes) {
  case_set<K> s{std::move(names), {}};
  std::size_t n = 1;
  for (const auto& a : axes) {
    if (a.empty()) throw parameter_error("ensemble::grid: an axis has no values");
    n *= a.size();
  }
  s.cases.reserve(n);
  std::array<std::size_t, K> at{};
  for (std::size_t i = 0; i < n; ++i) {
    std::array<double, K> c;
    for (int k = 0; k < K; ++k) c[k] = axes[k][at[k]];
    s.cases.push_back(c);
    for (int k = K - 1; k >= 0; --k) {
      if (++at[k] < axes[k].size()) break;
      at[k] = 0;
    }
  }
  return s;
}

/// The cases as given.
template <int K>
case_set<K> list(std::array<std::string, K> names, std::vector<std::array<double, K>> cases) {
  return {std::move(names), std::move(cases)};
}

/// A distribution to sample one parameter from.
struct distribution {
  enum class kind { fixed, uniform, normal, log_uniform } type = kind::fixed;
  double a = 0, b = 0;
};
inline distribution fixed(double v) { return {distribution::kind::fixed, v, v}; }
/// Uniform on [a, b).
inline distribution uniform(double a, double b) { return {distribution::kind::uniform, a, b}; }
/// Normal with this mean and standard deviation.
inline distribution normal(double mean, double sd) { return {distribution::kind::normal, mean, sd}; }
/// log x uniform on [log a, log b).
inline distribution log_uniform(double a, double b) { return {distribution::kind::log_uniform, a, b}; }

namespace detail {
/// A double uniform on [0, 1) from 53 random bits.
inline double unit(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }
inline double draw(const distribution& d, std::mt19937_64& g) {
  switch (d.type) {
    case distribution::kind::fixed:
      return d.a;
    case distribution::kind::uniform:
      return d.a + (d.b - d.a) * unit(g);
    case distribution::kind::log_uniform:
      return std::exp(std::log(d.a) + (std::log(d.b) - std::log(d.a)) * unit(g));
    case distribution::kind::normal: {
      // Box–Muller; 1 − u lies in (0, 1], so the logarithm is finite.
      const double u1 = 1.0 - unit(g), u2 = unit(g);
      return d.a + d.b * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }
  }
  return d.a;
}
}  // namespace detail

/// n cases, parameter k drawn from dists[k], from one seed.
template <int K>
case_set<K> sample(std::array<std::string, K> names, const std::array<distribution, K>& dists, std::size_t n,
                   std::uint64_t seed) {
  for (int k = 0; k < K; ++k) {
    const auto& d = dists[k];
    const bool bad = !std::isfinite(d.a) || !std::isfinite(d.b) ||
                     (d.type == distribution::kind::normal && d.b < 0) ||
                     (d.type == distribution::kind::log_uniform && !(d.a > 0 && d.b > 0));
    if (bad)
      throw parameter_error(::flange::detail::concat("ensemble::sample: the distribution of \"", names[k],
                                                     "\" has invalid bounds (", d.a, ", ", d.b, ")"));
  }
  case_set<K> s{std::move(names), {}};
  s.cases.resize(n);
  std::mt19937_64 g(seed);
  for (auto& c : s.cases)
    for (int k = 0; k < K; ++k) c[k] = detail::draw(dists[k], g);
  return s;
}

}  // namespace flange::ensemble
