// The C++ side of the Python benchmark (benchmarks/python/bench_python.py):
// the same work as a module's derivative and simulate, timed in C++ in the
// same process, so that the benchmark's ratio python_ns / cpp_ns is what
// Python costs. Bound only into modules built with TIMING
// (flange_add_python_module, cmake/flange_python.cmake).
//
//   _time_derivative(t, X, repeats)       median ns of one pass over the states X (k, n): plain calls
//   _time_simulate(x0, times, method, atol, repeats)   median ns of simulate(scene, x0, times)
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

#include "flange/python/module.hpp"

namespace flange::python {

namespace detail {
template <class F>
double median_ns(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    const auto b = std::chrono::steady_clock::now();
    t.push_back(std::chrono::duration<double, std::nano>(b - a).count());
  }
  std::nth_element(t.begin(), t.begin() + long(t.size() / 2), t.end());
  return t[t.size() / 2];
}
}  // namespace detail

template <class P, class Factory>
void bind_timing(py::module_& m, Factory) {
  m.def("_time_derivative", [](double t, py::handle X_in, int repeats) {
    using S = std::remove_cvref_t<std::invoke_result_t<const Factory&, const P&>>;
    const S scene = Factory{}(P{});
    const auto X = detail::numbers(X_in, "X");
    const std::size_t k = std::max<std::size_t>(detail::states_shape(X, S::n_state, "X"), 1);
    std::vector<typename S::state_type> xs(k), ds(k);
    for (std::size_t i = 0; i < k; ++i) std::copy_n(X.data() + i * S::n_state, S::n_state, xs[i].data());
    py::gil_scoped_release free;
    return detail::median_ns(repeats, [&] {
      for (std::size_t i = 0; i < k; ++i) scene(xs[i], ds[i], t);
      asm volatile("" : : "g"(ds.data()) : "memory");
    });
  });
  m.def("_time_simulate", [](py::handle x0_in, py::handle times_in, const std::string& method, double atol,
                             int repeats) {
    using S = std::remove_cvref_t<std::invoke_result_t<const Factory&, const P&>>;
    const S scene = Factory{}(P{});
    const auto x0 = detail::one_state<typename S::state_type>(x0_in, "x0");
    const auto times = detail::times_of(times_in);
    py::gil_scoped_release free;
    return detail::with_method(method, [&](auto meth) {
      return detail::median_ns(repeats, [&] {
        auto tr = flange::simulate<decltype(meth)>(scene, x0, times, {.tolerance = atol});
        asm volatile("" : : "g"(tr.x.data()) : "memory");
      });
    });
  });
}

}  // namespace flange::python
