// Forward-mode dual numbers: a value and N partial derivatives, carried
// through the scalar-templated dynamics so that the derivative's Jacobian is
// exact (no finite-difference step to choose). Eigen sees dual as a scalar type
// through its NumTraits.
#pragma once
#include <cmath>
#include <limits>
#include <ostream>
#include <type_traits>

#include <Eigen/Core>

namespace flange {

/// Whether x is exactly zero: for a floating-point scalar, x == 0; for a
/// dual number (below), its value and its derivatives. A product with it
/// adds nothing to a sum, value or derivative.
template <class T>
  requires std::is_floating_point_v<T>
constexpr bool exactly_zero(T x) {
  return x == T(0);
}

namespace detail {
/// A dual number's N derivatives. From three on, held as chunks of two
/// numbers (GCC's vector extension, which clang shares): each operation of a
/// dual number is then one instruction a chunk, as written, rather than
/// whatever g++ makes of its loop over N numbers. Each lane is computed by
/// itself, so the numbers are the same; the time is less (the crane's
/// dual-number Jacobian 256 → 199 ns, the spatial arm's, whose PD laws'
/// forces are dual numbers, 601 → 501 ns: docs/performance.md, "The
/// Jacobian").
/// Read and written a number at a time by index. One or two derivatives
/// stay a number each: as one chunk the paper's arm (two states) took
/// longer (docs/performance.md, "The Jacobian").
template <class T, bool Chunked>
struct chunk_of {
  using type = T;
  static constexpr int width = 1;
};
template <class T>
struct chunk_of<T, true> {
  typedef T type __attribute__((vector_size(2 * sizeof(T))));
  static constexpr int width = 2;
};
template <class T, int N>
struct lanes {
  using chunk_type = chunk_of<T, (N >= 3)>;
  using chunk = typename chunk_type::type;
  static constexpr int chunks = (N + chunk_type::width - 1) / chunk_type::width;
  chunk c[chunks];
  T& operator[](int k) { return begin()[k]; }
  const T& operator[](int k) const { return begin()[k]; }
  T* begin() { return reinterpret_cast<T*>(c); }
  T* end() { return begin() + N; }
  const T* begin() const { return reinterpret_cast<const T*>(c); }
  const T* end() const { return begin() + N; }
};
}  // namespace detail

template <class T, int N>
struct dual {
  /// Chunks of lanes: operations below go a chunk at a time.
  static constexpr int C = detail::lanes<T, N>::chunks;
  T v;
  detail::lanes<T, N> d;

  /// Not initialized, as a double is not: nothing is zeroed until written
  /// (Eigen's matrices of dual numbers, made for every product and sum,
  /// zeroed each entry: the four-bar's Jacobian took 2.4 µs against 1.4).
  constexpr dual() = default;
  constexpr dual(T value) : v(value), d{} {}  // NOLINT: a constant is a dual with zero derivatives
  template <class U>
    requires std::is_arithmetic_v<U>
  constexpr dual(U value) : v(T(value)), d{} {}  // NOLINT
  /// A number with derivative lane(k) in direction k, its lanes made a
  /// chunk at a time in registers. (A lane written alone into a chunk
  /// written before, the chunk read whole soon after: the read waits until
  /// the write reaches the cache. The spatial arm's PD laws cost its
  /// Jacobian 95 ns that way, 25 ns made whole.)
  template <class F>
  static dual with_lanes(T value, F&& lane) {
    dual r;
    r.v = value;
    if constexpr (C == N) {
      for (int k = 0; k < N; ++k) r.d.c[k] = lane(k);
    } else {
      for (int j = 0; j < C; ++j)
        r.d.c[j] = typename detail::lanes<T, N>::chunk{lane(2 * j), 2 * j + 1 < N ? lane(2 * j + 1) : T(0)};
    }
    return r;
  }
  /// x with ∂x/∂x_k = 1 (seeding direction k), made whole (with_lanes).
  static dual variable(T value, int k) {
    return with_lanes(value, [k](int j) { return T(j == k); });
  }
  explicit operator double() const { return static_cast<double>(v); }
  explicit operator long double() const { return static_cast<long double>(v); }

  dual& operator+=(const dual& o) {
    v += o.v;
    for (int k = 0; k < C; ++k) d.c[k] += o.d.c[k];
    return *this;
  }
  dual& operator-=(const dual& o) {
    v -= o.v;
    for (int k = 0; k < C; ++k) d.c[k] -= o.d.c[k];
    return *this;
  }
  dual& operator*=(const dual& o) {
    for (int k = 0; k < C; ++k) d.c[k] = d.c[k] * o.v + v * o.d.c[k];
    v *= o.v;
    return *this;
  }
  dual& operator/=(const dual& o) {
    const T inv = T(1) / o.v;
    v *= inv;
    for (int k = 0; k < C; ++k) d.c[k] = (d.c[k] - v * o.d.c[k]) * inv;
    return *this;
  }
  // Each result is built in place from both operands and returned by name,
  // repeating the arithmetic of the compound operators above: a copy of a
  // changed by `op=` (taken by value and returned as `a op= b`, or copied
  // into a named result) moves N + 1 numbers in and out of every operation,
  // which g++ 12 does not elide. Either way round a floating quadruped's
  // dual-number Jacobian took 1.4–1.8 times as long.
  friend dual operator+(const dual& a, const dual& b) {
    dual r;
    r.v = a.v + b.v;
    for (int k = 0; k < C; ++k) r.d.c[k] = a.d.c[k] + b.d.c[k];
    return r;
  }
  friend dual operator-(const dual& a, const dual& b) {
    dual r;
    r.v = a.v - b.v;
    for (int k = 0; k < C; ++k) r.d.c[k] = a.d.c[k] - b.d.c[k];
    return r;
  }
  friend dual operator*(const dual& a, const dual& b) {
    dual r;
    r.v = a.v * b.v;
    for (int k = 0; k < C; ++k) r.d.c[k] = a.d.c[k] * b.v + a.v * b.d.c[k];
    return r;
  }
  friend dual operator/(const dual& a, const dual& b) {
    const T inv = T(1) / b.v;
    dual r;
    r.v = a.v * inv;
    for (int k = 0; k < C; ++k) r.d.c[k] = (a.d.c[k] - r.v * b.d.c[k]) * inv;
    return r;
  }
  // With a constant (a T): nothing is computed for its derivatives, which
  // are zero. The same numbers as through dual(b), but for the sign of a
  // zero derivative.
  friend dual operator+(const dual& a, T b) {
    dual r = a;
    r.v += b;
    return r;
  }
  friend dual operator+(T a, const dual& b) { return b + a; }
  friend dual operator-(const dual& a, T b) {
    dual r = a;
    r.v -= b;
    return r;
  }
  friend dual operator-(T a, const dual& b) {
    dual r;
    r.v = a - b.v;
    for (int k = 0; k < C; ++k) r.d.c[k] = -b.d.c[k];
    return r;
  }
  friend dual operator*(const dual& a, T b) {
    dual r;
    r.v = a.v * b;
    for (int k = 0; k < C; ++k) r.d.c[k] = a.d.c[k] * b;
    return r;
  }
  friend dual operator*(T a, const dual& b) { return b * a; }
  friend dual operator/(const dual& a, T b) {
    const T inv = T(1) / b;
    dual r;
    r.v = a.v * inv;
    for (int k = 0; k < C; ++k) r.d.c[k] = a.d.c[k] * inv;
    return r;
  }
  friend dual operator-(const dual& a) {
    dual r;
    r.v = -a.v;
    for (int k = 0; k < C; ++k) r.d.c[k] = -a.d.c[k];
    return r;
  }
  friend dual operator+(const dual& a) { return a; }
  friend bool operator<(const dual& a, const dual& b) { return a.v < b.v; }
  friend bool operator>(const dual& a, const dual& b) { return a.v > b.v; }
  friend bool operator<=(const dual& a, const dual& b) { return a.v <= b.v; }
  friend bool operator>=(const dual& a, const dual& b) { return a.v >= b.v; }
  friend bool operator==(const dual& a, const dual& b) { return a.v == b.v; }
  friend bool operator!=(const dual& a, const dual& b) { return a.v != b.v; }

  /// f(a) with f(a.v) = fv and f'(a.v) = dfv.
  friend dual chain(const dual& a, T fv, T dfv) {
    dual r(fv);
    for (int k = 0; k < C; ++k) r.d.c[k] = dfv * a.d.c[k];
    return r;
  }
  friend dual sin(const dual& a) {
    using std::cos;
    using std::sin;
    return chain(a, sin(a.v), cos(a.v));
  }
  friend dual cos(const dual& a) {
    using std::cos;
    using std::sin;
    return chain(a, cos(a.v), -sin(a.v));
  }
  friend dual tanh(const dual& a) {
    using std::tanh;
    const T th = tanh(a.v);
    return chain(a, th, T(1) - th * th);
  }
  friend dual sqrt(const dual& a) {
    using std::sqrt;
    const T s = sqrt(a.v);
    return chain(a, s, T(0.5) / s);
  }
  friend dual abs(const dual& a) { return a.v < T(0) ? -a : a; }
  friend dual atan2(const dual& y, const dual& x) {
    using std::atan2;
    const T r2 = x.v * x.v + y.v * y.v;
    dual r(atan2(y.v, x.v));
    for (int k = 0; k < C; ++k) r.d.c[k] = (x.v * y.d.c[k] - y.v * x.d.c[k]) / r2;
    return r;
  }
  friend bool isfinite(const dual& a) {
    using std::isfinite;
    if (!isfinite(a.v)) return false;
    for (const auto& x : a.d)
      if (!isfinite(x)) return false;
    return true;
  }
  friend std::ostream& operator<<(std::ostream& os, const dual& a) { return os << a.v; }
  /// exactly_zero (above) of a dual: its value and its derivatives (a == 0
  /// compares values only).
  friend bool exactly_zero(const dual& a) {
    if (!exactly_zero(a.v)) return false;
    for (const auto& x : a.d)
      if (!exactly_zero(x)) return false;
    return true;
  }
};

// Made and copied as a double is: Eigen's matrices of dual numbers
// (RequireInitialization = 0 below) make and copy them without a constructor
// call.
static_assert(std::is_trivially_default_constructible_v<dual<double, 3>> &&
              std::is_trivially_copyable_v<dual<double, 3>>);

}  // namespace flange

namespace Eigen {
template <class T, int N>
struct NumTraits<flange::dual<T, N>> : NumTraits<T> {
  using Real = flange::dual<T, N>;
  using NonInteger = flange::dual<T, N>;
  using Nested = flange::dual<T, N>;
  using Literal = flange::dual<T, N>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1 + N,
    AddCost = 1 + N,
    MulCost = 1 + 2 * N
  };
};
}  // namespace Eigen
