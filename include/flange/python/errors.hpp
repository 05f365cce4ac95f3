// flange's errors as Python exceptions: the `flange` package's classes
// (python/flange/__init__.py), which every scene module shares, and the
// translation of flange's C++ exceptions into them (python/module.hpp
// registers it):
//   simulation_error  → flange.SimulationError (.time, .state, .reason)
//   unknown_name      → flange.UnknownNameError (a KeyError)
//   parameter_error   → flange.ParameterError (a ValueError)
//   error             → flange.Error
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <exception>
#include <string>
#include <string_view>

#include "flange/errors.hpp"
#include "flange/python/parameters.hpp"

namespace flange::python {
namespace py = pybind11;

namespace detail {
using flange::detail::concat;
/// The `flange` package's classes (python/flange/__init__.py), looked up once.
struct package {
  py::object error, parameter_error, simulation_error, unknown_name, trajectory, ensemble_result;
};
inline package& classes() {
  static auto* p = new package;  // never destroyed: outlives the interpreter's teardown
  return *p;
}
inline void load_package() {
  py::module_ f;
  try {
    f = py::module_::import("flange");
  } catch (py::error_already_set& e) {
    if (std::string_view(e.what()).find("numpy") != std::string_view::npos) {
      // The package is there; this interpreter has no numpy (often a pyenv
      // or virtualenv python3 first on PATH, not the one the module is for).
      const auto here = py::str(py::module_::import("sys").attr("executable")).cast<std::string>();
      throw py::import_error(concat("flange scene modules need numpy, which this Python (", here,
                                    ") cannot import: run them with the Python they were built for",
#ifdef FLANGE_PYTHON_BUILT_FOR
                                    " (", FLANGE_PYTHON_BUILT_FOR, ")",
#endif
                                    " (the python3 beside the module runs it with the module's directory on its "
                                    "path), or install numpy for this one"));
    }
    throw py::import_error(concat("a flange scene module needs the `flange` Python package beside it ",
                                  "(flange_add_python_module puts it there): ", e.what()));
  }
  auto& c = classes();
  c.error = f.attr("Error");
  c.parameter_error = f.attr("ParameterError");
  c.simulation_error = f.attr("SimulationError");
  c.unknown_name = f.attr("UnknownNameError");
  c.trajectory = f.attr("Trajectory");
  c.ensemble_result = f.attr("EnsembleResult");
}
inline void raise(const py::object& type, const py::object& value) { PyErr_SetObject(type.ptr(), value.ptr()); }
/// flange's C++ exceptions as the package's Python ones.
inline void translate(std::exception_ptr p) {
  const auto& c = classes();
  try {
    std::rethrow_exception(p);
  } catch (const simulation_error& e) {
    py::array_t<double> x(static_cast<py::ssize_t>(e.state.size()));
    std::copy(e.state.begin(), e.state.end(), x.mutable_data());
    raise(c.simulation_error, c.simulation_error(e.what(), e.time, x, e.reason.empty() ? e.what() : e.reason));
  } catch (const unknown_name& e) {
    raise(c.unknown_name, c.unknown_name(e.what()));
  } catch (const parameter_error& e) {
    raise(c.parameter_error, c.parameter_error(e.what()));
  } catch (const error& e) {
    raise(c.error, c.error(e.what()));
  }
}
}  // namespace detail

}  // namespace flange::python
