// numpy arrays for a scene module (python/module.hpp): states read where
// they lie (no copy for a C-contiguous float64 array), shapes and dtypes
// checked with a message that says what was expected, and results handed to
// numpy without a copy.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flange/errors.hpp"
#include "flange/math/types.hpp"

namespace flange::python {
namespace py = pybind11;

namespace detail {
using flange::detail::concat;

/// A state as the scene's derivative reads it, over numpy's memory: no copy.
struct state_span {
  double* p;
  std::size_t n;
  [[nodiscard]] std::size_t size() const { return n; }
  [[nodiscard]] double* data() const { return p; }
  double& operator[](std::size_t i) const { return p[i]; }
};

using f64 = py::array_t<double, py::array::c_style | py::array::forcecast>;
inline std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += concat(i ? ", " : "", a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}
/// obj as a C-contiguous float64 array: numbers only (integers are
/// converted, no copy for a float64 C-contiguous array); ValueError otherwise.
inline f64 numbers(py::handle obj, std::string_view what) {
  if (py::isinstance<py::array>(obj)) {
    const auto a = py::reinterpret_borrow<py::array>(obj);
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
      throw parameter_error(concat("flange: ", what, " has dtype ", std::string(py::str(a.dtype())),
                                   "; give float64 numbers"));
  }
  auto a = f64::ensure(obj);
  if (!a) {
    PyErr_Clear();
    throw parameter_error(concat("flange: ", what, " is not an array of numbers (got ",
                                 std::string(py::str(py::type::of(obj))), ")"));
  }
  return a;
}
/// One state (n,) or a stack of them (k, n): k, or 0 for one state.
inline std::size_t states_shape(const f64& a, std::size_t n, std::string_view what) {
  if (a.ndim() == 1 && std::size_t(a.shape(0)) == n) return 0;
  if (a.ndim() == 2 && std::size_t(a.shape(1)) == n) return std::size_t(a.shape(0));
  throw parameter_error(concat("flange: ", what, " has shape ", shape_of(a), "; the scene's states have shape (", n,
                               ",) (x = (q, v)), or (k, ", n, ") for k of them"));
}
/// One state, shape (n,), copied into the scene's state type.
template <class X>
X one_state(py::handle obj, std::string_view what) {
  const auto a = numbers(obj, what);
  X x;
  if (states_shape(a, x.size(), what) != 0 || a.ndim() != 1)
    throw parameter_error(concat("flange: ", what, " has shape ", shape_of(a), "; give one state, shape (", x.size(),
                                 ",)"));
  std::copy(a.data(), a.data() + x.size(), x.data());
  return x;
}
inline void require_finite_time(double t, std::string_view what) {
  if (!std::isfinite(t)) throw parameter_error(concat("flange: ", what, " = ", t, " is not finite"));
}
/// A vector's memory handed to numpy, without a copy: the array owns it.
template <class T>
py::array_t<double> own(std::vector<T>&& v, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(v));
  py::capsule free(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<double>(shape, reinterpret_cast<const double*>(held->data()), free);
}
template <class V>
py::array_t<double> array_of(const V& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  for (std::size_t i = 0; i < std::size_t(v.size()); ++i) a.mutable_data()[i] = v[i];
  return a;
}
inline py::array_t<double> matrix_of(const Mat3d& m) {
  py::array_t<double> a({3, 3});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.mutable_data()[3 * i + j] = m(i, j);
  return a;
}
inline std::vector<double> times_of(py::handle obj) {
  const auto a = numbers(obj, "times");
  if (a.ndim() != 1) throw parameter_error(concat("flange: times has shape ", shape_of(a), "; give a 1-D array"));
  return {a.data(), a.data() + a.size()};
}

}  // namespace detail

}  // namespace flange::python
