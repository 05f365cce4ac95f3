// A joint's state from a Python value, for initial_state(**joints)
// (python/module.hpp): a number or nq numbers (q), or a dict of the joint's
// own fields (q and v; R and w; r, v, R, w and v_cm), an orientation as a 3×3
// matrix or {"rpy"}, {"cardan"}, {"axis", "angle"}. A field the joint does not
// have is an unknown_name naming the closest one and listing the fields.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flange/core/joint.hpp"
#include "flange/detail/closest_name.hpp"
#include "flange/math/rotation.hpp"
#include "flange/python/arrays.hpp"
#include "flange/python/parameters.hpp"

namespace flange::python {
namespace py = pybind11;

namespace detail {
using flange::detail::concat;

inline Vec3d vec3(py::handle v, std::string_view what) {
  const auto a = numbers(v, what);
  if (a.size() != 3) throw parameter_error(concat("flange: ", what, " has shape ", shape_of(a), "; give 3 numbers"));
  return {a.data()[0], a.data()[1], a.data()[2]};
}
/// An orientation: a 3×3 rotation matrix, or {"rpy": (roll, pitch, yaw)},
/// {"cardan": (a, b, c)}, {"axis": (x, y, z), "angle": a}.
inline orientation orientation_of(py::handle v, std::string_view what) {
  if (py::isinstance<py::dict>(v)) {
    const auto d = py::reinterpret_borrow<py::dict>(v);
    if (d.contains("rpy")) {
      const Vec3d a = vec3(d["rpy"], concat(what, "[\"rpy\"]"));
      return orientation::rpy(a(0), a(1), a(2));
    }
    if (d.contains("cardan")) {
      const Vec3d a = vec3(d["cardan"], concat(what, "[\"cardan\"]"));
      return orientation::cardan(a(0), a(1), a(2));
    }
    if (d.contains("axis") && d.contains("angle")) {
      const Vec3d n = vec3(d["axis"], concat(what, "[\"axis\"]"));
      if (!(n.norm() > 0)) throw parameter_error(concat("flange: ", what, "[\"axis\"] is zero"));
      return orientation::axis_angle(n, py::cast<double>(d["angle"]));
    }
    throw unknown_name(concat("flange: ", what, " is a dict without \"rpy\", \"cardan\" or \"axis\" and \"angle\""));
  }
  const auto a = numbers(v, what);
  if (!(a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3))
    throw parameter_error(concat("flange: ", what, " has shape ", shape_of(a),
                                 "; give a 3×3 rotation matrix or {\"rpy\": (r, p, y)}"));
  Mat3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = a.data()[3 * i + j];
  return orientation::matrix(R);
}
inline void assign(double& m, py::handle v, std::string_view what) {
  try {
    m = py::cast<double>(v);
  } catch (const py::cast_error&) {
    throw parameter_error(concat("flange: ", what, " is not a number"));
  }
}
template <std::size_t N>
void assign(std::array<double, N>& m, py::handle v, std::string_view what) {
  const auto a = numbers(v, what);
  if (std::size_t(a.size()) != N)
    throw parameter_error(concat("flange: ", what, " has shape ", shape_of(a), "; give ", N, " numbers"));
  std::copy(a.data(), a.data() + N, m.begin());
}
inline void assign(Vec3d& m, py::handle v, std::string_view what) { m = vec3(v, what); }
inline void assign(std::optional<Vec3d>& m, py::handle v, std::string_view what) { m = vec3(v, what); }
inline void assign(orientation& m, py::handle v, std::string_view what) { m = orientation_of(v, what); }

/// Sets field `key` of a joint's state type St, if it has one by that name.
template <class St>
bool set_field(St& s, std::string_view key, py::handle v, std::string_view what) {
  const std::string w = concat(what, "[\"", key, "\"]");
  if (key == "q") {
    if constexpr (requires { s.q; }) return assign(s.q, v, w), true;
  } else if (key == "v") {
    if constexpr (requires { s.v; }) return assign(s.v, v, w), true;
  } else if (key == "r") {
    if constexpr (requires { s.r; }) return assign(s.r, v, w), true;
  } else if (key == "R") {
    if constexpr (requires { s.R; }) return assign(s.R, v, w), true;
  } else if (key == "w") {
    if constexpr (requires { s.w; }) return assign(s.w, v, w), true;
  } else if (key == "v_cm") {
    if constexpr (requires { s.v_cm; }) return assign(s.v_cm, v, w), true;
  }
  return false;
}
template <class St>
std::vector<std::string> fields_of() {
  St s{};
  std::vector<std::string> f;
  if constexpr (requires { s.q; }) f.emplace_back("q");
  if constexpr (requires { s.r; }) f.emplace_back("r");
  if constexpr (requires { s.v; }) f.emplace_back("v");
  if constexpr (requires { s.R; }) f.emplace_back("R");
  if constexpr (requires { s.w; }) f.emplace_back("w");
  if constexpr (requires { s.v_cm; }) f.emplace_back("v_cm");
  return f;
}
/// A joint's state from a Python value: a dict of its fields, or, for a
/// joint with coordinates q, q alone (a number, or nq numbers).
template <class J>
joint_state_t<J> joint_value(py::handle v) {
  using St = joint_state_t<J>;
  St s{};
  const std::string what = concat(J::type_name, " \"", J::name.view(), "\"");
  if (py::isinstance<py::dict>(v)) {
    for (auto [k, value] : py::reinterpret_borrow<py::dict>(v)) {
      const std::string key = py::str(k);
      if (!set_field(s, key, value, what)) {
        const auto fields = fields_of<St>();
        std::string list;
        for (const auto& f : fields) list += concat(list.empty() ? "" : ", ", f);
        throw unknown_name(concat("flange: ", what, " has no state field \"", key, "\"; did you mean \"",
                                  fields[flange::detail::closest_name(key, fields)], "\"? Its fields are ", list));
      }
    }
  } else if constexpr (requires { s.q; }) {
    assign(s.q, v, concat(what, "'s q"));
  } else {
    throw parameter_error(concat("flange: ", what, " is set from a dict of its fields, not from ",
                                 std::string(py::str(py::type::of(v)))));
  }
  return s;
}

}  // namespace detail

}  // namespace flange::python
