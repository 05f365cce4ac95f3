// A compiled scene as a Python module: pybind11, numpy arrays in and out.
//
//   PYBIND11_MODULE(crane, m) {
//     flange::python::bind<crane_params>(m, [](const crane_params& p) { return make_crane(p); });
//   }
//
// cmake/flange_python.cmake writes this for a header and a factory
// (flange_add_python_module), or for a URDF file (flange_urdf_python_module).
// The factory builds the scene from its run-time parameters (a struct
// adapted to Boost.Hana, python/parameters.hpp, or no_parameters): the
// scene's type is compiled once, its parameters are numbers Python sets.
//
// What the module has (docs/python.md):
//   n_q, n_v, n_state, joints, state_names, joint_layout, parameters, frames, internals
//   Scene(**parameters)        the scene at these parameters; module functions use Scene()
//   initial_state(**joints)    joints by name (a number: q; a dict: {"q", "v"}, {"R", "w"}, …)
//   derivative(t, x[, out])    x of shape (n_state,) or (k, n_state)
//   jacobian(t, x)             ∂ẋ/∂x, exact (flange::jacobian: analytic or dual numbers)
//   simulate(x0, times, method="dopri5" | "rosenbrock4", atol, rtol, dt, max_rhs_evals)
//   recover(t, x), energy(x[, t]), momentum(x), bodies()
//   ensemble(cases, times, x0, recorders, …)   the C++ ensemble engine (oneTBB threads where
//                              built with it), recorders as python/recorders.hpp lists them
// Module functions take params={name: value} for one call. Failures raise
// the `flange` package's exceptions (python/flange/__init__.py):
// SimulationError (time, state, reason), ParameterError (a ValueError),
// UnknownNameError (a KeyError, with the closest name). Every long call
// releases the GIL.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "flange/ensemble/ensemble.hpp"
#include "flange/flange.hpp"
#include "flange/python/arrays.hpp"
#include "flange/python/errors.hpp"
#include "flange/python/joint_values.hpp"
#include "flange/python/parameters.hpp"
#include "flange/python/recorders.hpp"
#include "flange/simulate/rosenbrock4.hpp"
#ifdef FLANGE_PYTHON_TBB
#include "flange/ensemble/tbb.hpp"
#endif

namespace flange::python {
namespace py = pybind11;

namespace detail {
using flange::detail::concat;

template <class P, class Factory>
struct bound {
  using scene_type = std::remove_cvref_t<std::invoke_result_t<const Factory&, const P&>>;
  using S = scene_type;
  using X = typename S::state_type;
  using factory_type = Factory;
  P params;
  S scene;
  explicit bound(const P& p) : params(p), scene(Factory{}(params)) {}

  static P params_from(const py::dict& d) {
    P p{};
    for (auto [k, v] : d) {
      double value;
      try {
        value = py::cast<double>(v);
      } catch (const py::cast_error&) {
        throw parameter_error(concat("flange: parameter \"", std::string(py::str(k)), "\" is not a number"));
      }
      set_parameter(p, std::string(py::str(k)), value);
    }
    return p;
  }

  /// The component index of the joint named `name`, or unknown_name.
  static int joint_index(std::string_view name) {
    try {
      return flange::detail::joint_named<S>(name);
    } catch (const parameter_error& e) {
      throw unknown_name(e.what());
    }
  }

  [[nodiscard]] py::array_t<double> initial_state(const py::kwargs& joints) const {
    X x = neutral_state(scene);
    // every joint first, then what depends on the others (a FreeMotion's v_cm)
    for (int pass = 0; pass < 2; ++pass)
      for (auto [k, v] : joints) {
        const int c = joint_index(std::string(py::str(k)));
        flange::detail::for_links<S>([&](auto l) {
          using LI = flange::detail::link_info<S, decltype(l)::value>;
          constexpr int C = LI::joint;
          if (C != c) return;
          const auto value = joint_value<typename S::template component_type<C>>(v);
          if (pass == 0) flange::detail::write_joint<S, X, C>(scene, x, value);
          else flange::detail::finish_joint<S, X, C>(scene, x, value);
        });
      }
    return array_of(x);
  }

  [[nodiscard]] py::array_t<double> derivative(double t, py::handle x_in, py::handle out_in) const {
    require_finite_time(t, "t");
    const auto x = numbers(x_in, "x");
    const std::size_t k = states_shape(x, S::n_state, "x");
    py::array_t<double> out;
    if (out_in.is_none()) {
      out = k ? py::array_t<double>({py::ssize_t(k), py::ssize_t(S::n_state)}) : py::array_t<double>(S::n_state);
    } else {
      if (!py::isinstance<py::array_t<double, py::array::c_style>>(out_in))
        throw parameter_error("flange: out must be a C-contiguous float64 array");
      out = py::reinterpret_borrow<py::array_t<double>>(out_in);
      if (out.ndim() != x.ndim() || out.size() != x.size())
        throw parameter_error(concat("flange: out has shape ", shape_of(out), "; it must have x's, ", shape_of(x)));
    }
    const double* xs = x.data();
    double* d = out.mutable_data();
    const auto one = [&](std::size_t i) {
      state_span xi{const_cast<double*>(xs + i * S::n_state), S::n_state}, di{d + i * S::n_state, S::n_state};
      if (!flange::detail::finite(xi)) [[unlikely]]
        throw parameter_error(concat("flange: derivative: x", k ? concat("[", i, "]") : "", " is not finite: ",
                                     flange::detail::describe(xi)));
      scene(xi, di, t);
      if (!flange::detail::finite(di)) [[unlikely]]
        flange::detail::fail_at("the derivative is not finite", xi, t);
    };
    if (k == 0) {
      one(0);
    } else {
      py::gil_scoped_release free;
      for (std::size_t i = 0; i < k; ++i) one(i);
    }
    return out;
  }

  [[nodiscard]] py::array_t<double> jacobian(double t, py::handle x_in) const {
    require_finite_time(t, "t");
    const X x = one_state<X>(x_in, "x");
    const auto J = flange::jacobian(scene, t, x);
    py::array_t<double> a({py::ssize_t(S::n_state), py::ssize_t(S::n_state)});
    for (int i = 0; i < S::n_state; ++i)
      for (int j = 0; j < S::n_state; ++j) a.mutable_data()[i * S::n_state + j] = J(i, j);
    return a;
  }

  [[nodiscard]] py::dict energy(py::handle x_in, double t) const {
    require_finite_time(t, "t");
    const X x = one_state<X>(x_in, "x");
    const auto e = flange::energy(scene, t, x);
    py::dict d;
    d["kinetic"] = e.kinetic;
    d["gravity_potential"] = e.gravity_potential;
    d["elastic_potential"] = e.elastic_potential;
    d["total"] = e.total();
    return d;
  }

  [[nodiscard]] py::dict momentum(py::handle x_in) const {
    const X x = one_state<X>(x_in, "x");
    const auto h = flange::momentum(scene, x);
    py::dict d;
    d["linear"] = array_of(h.linear);
    d["angular"] = array_of(h.angular);
    return d;
  }

  [[nodiscard]] py::list bodies() const {
    py::list l;
    for (const auto& b : flange::bodies(scene)) {
      py::dict d;
      d["name"] = std::string(b.name);
      d["m"] = b.m;
      d["r_cm"] = array_of(b.r_cm);
      d["J"] = matrix_of(b.J);
      l.append(d);
    }
    return l;
  }

  [[nodiscard]] py::dict recover(double t, py::handle x_in) const {
    require_finite_time(t, "t");
    const X x = one_state<X>(x_in, "x");
    const auto s = flange::recover(scene, t, x);
    py::dict out, frames, internals;
    out["t"] = t;
    out["q"] = array_of(s.q);
    out["v"] = array_of(s.v);
    out["vdot"] = array_of(s.vdot);
    py::dict e;
    e["kinetic"] = s.kinetic;
    e["gravity_potential"] = s.gravity_potential;
    e["elastic_potential"] = s.elastic_potential;
    e["total"] = s.total();
    out["energy"] = e;
    for (int c = 0; c < S::n_components; ++c)
      for (int k = 0; k < S::table.nframes[c]; ++k) {
        const int f = S::table.frame_base[c] + k;
        const auto& fk = s.frames[f];
        py::dict d;
        d["r"] = array_of(fk.r);
        d["R"] = matrix_of(fk.R);
        d["v"] = array_of(fk.v);
        d["w"] = array_of(fk.w);
        d["a"] = array_of(fk.a);
        d["wd"] = array_of(fk.wd);
        d["f"] = array_of(s.cut[f].f);
        d["tau"] = array_of(s.cut[f].n);
        frames[py::str(concat(S::table.names[c], ".", S::table.frame_names[c][k]))] = d;
      }
    out["frames"] = frames;
    flange::detail::static_for<S::n_components>([&](auto ci) {
      constexpr int c = decltype(ci)::value;
      using C = typename S::template component_type<c>;
      for (int i = 0; i < int(C::internals.size()); ++i) {
        const int o = S::template slot_offset<c>(4 * int(C::frames.size()) + i);
        const std::string name = concat(S::table.names[c], ".", flange::detail::internal_ascii<C>[i].view());
        switch (C::internals[i].kind) {
          case expr::var_kind::scalar: internals[py::str(name)] = s.y(o); break;
          case expr::var_kind::vec: internals[py::str(name)] = array_of(Vec3d(s.y.template segment<3>(o))); break;
          default: internals[py::str(name)] = matrix_of(Mat3d(Eigen::Map<const Mat3d>(s.y.data() + o))); break;
        }
      }
    });
    out["internals"] = internals;
    return out;
  }
};

/// Which method a name means; calls f(method type).
template <class F>
decltype(auto) with_method(const std::string& name, F&& f) {
  if (name == "dopri5") return f(method::dopri5{});
  if (name == "rosenbrock4") return f(method::rosenbrock4{});
  throw parameter_error(concat("flange: method \"", name, "\" is not one this module has: dopri5 (the default, ",
                               "error-controlled Dormand–Prince 5(4)) or rosenbrock4 (stiff scenes, exact Jacobian)"));
}
inline simulate_options options_of(double atol, const py::object& rtol, double dt, long max_rhs_evals) {
  simulate_options o{.tolerance = atol, .dt = dt, .max_rhs_evals = max_rhs_evals};
  if (!rtol.is_none()) o.rel_tolerance = py::cast<double>(rtol);
  return o;
}

template <class B>
py::object simulate(const B& b, py::handle x0_in, py::handle times_in, const std::string& method, double atol,
                    const py::object& rtol, double dt, long max_rhs_evals) {
  using X = typename B::X;
  const X x0 = one_state<X>(x0_in, "x0");
  const std::vector<double> times = times_of(times_in);
  const simulate_options o = options_of(atol, rtol, dt, max_rhs_evals);
  trajectory<X> tr;
  {
    py::gil_scoped_release free;
    tr = with_method(method, [&](auto m) { return flange::simulate<decltype(m)>(b.scene, x0, times, o); });
  }
  const auto n_t = static_cast<py::ssize_t>(tr.t.size());
  return classes().trajectory(own(std::move(tr.t), {n_t}), own(std::move(tr.x), {n_t, py::ssize_t(B::S::n_state)}),
                              tr.steps, tr.rhs_evals);
}

/// The state's entries by name: "elbow.q", "base.q[3]", "base.v[0]", …
template <class S>
std::vector<std::string> state_names() {
  std::vector<std::string> names(S::n_state);
  for (int c = 0; c < S::n_components; ++c) {
    if (S::tree.q_offset[c] < 0) continue;
    const auto label = [&](const char* what, int n, int i) {
      return concat(S::table.names[c], ".", what, n > 1 ? concat("[", i, "]") : "");
    };
    for (int i = 0; i < S::table.nq[c]; ++i) names[S::tree.q_offset[c] + i] = label("q", S::table.nq[c], i);
    for (int i = 0; i < S::table.nv[c]; ++i) names[S::n_q + S::tree.v_offset[c] + i] = label("v", S::table.nv[c], i);
  }
  return names;
}

/// The recorders a Python dict asks for: {name: (kind, quantity, numbers…)}.
template <class S>
recorder_set recorders_of(py::handle in, std::vector<std::string>& names) {
  recorder_set set;
  if (in.is_none()) return set;
  if (!py::isinstance<py::dict>(in))
    throw parameter_error("flange: ensemble: recorders is a dict {name: (kind, quantity, numbers…)}");
  const auto states = state_names<S>();
  for (auto [k, spec] : py::reinterpret_borrow<py::dict>(in)) {
    const std::string name = py::str(k);
    if (set.n == max_recorders)
      throw parameter_error(concat("flange: ensemble: at most ", max_recorders, " recorders"));
    if (!py::isinstance<py::tuple>(spec) || py::len(spec) < 2)
      throw parameter_error(concat("flange: ensemble: recorder \"", name, "\" is a tuple (kind, quantity, numbers…), ",
                                   "such as (\"max_abs\", \"pivot.q\", -1.57)"));
    const auto t = py::reinterpret_borrow<py::tuple>(spec);
    const std::string kind = py::str(t[0]), of = py::str(t[1]);
    quantity q;
    if (of != "energy") {
      const auto it = std::find(states.begin(), states.end(), of);
      if (it == states.end()) {
        auto options = states;
        options.push_back("energy");
        throw unknown_name(concat("flange: ensemble: recorder \"", name, "\": the scene has no state entry \"", of,
                                  "\"; did you mean \"", options[flange::detail::closest_name(of, options)], "\"?"));
      }
      q.index = int(it - states.begin());
    }
    std::array<double, 4> args{};
    const int n_args = int(py::len(t)) - 2;
    if (n_args > int(args.size())) throw parameter_error(concat("flange: ensemble: recorder \"", name, "\": too many numbers"));
    for (int i = 0; i < n_args; ++i) {
      try {
        args[i] = py::cast<double>(t[i + 2]);
      } catch (const py::cast_error&) {
        throw parameter_error(concat("flange: ensemble: recorder \"", name, "\": argument ", i + 3, " is not a number"));
      }
    }
    set.recs[set.n++] = make_recorder(kind, q, args.data(), n_args);
    names.push_back(name);
  }
  return set;
}

template <class B>
py::object ensemble(py::handle cases_in, py::handle times_in, py::handle x0_in, py::handle recorders_in,
                    const std::string& method, double atol, const py::object& rtol, double dt, long max_rhs_evals,
                    int threads) {
  using S = typename B::S;
  using X = typename B::X;
  using P = decltype(B::params);
  const std::vector<double> times = times_of(times_in);
  flange::detail::check_times(times);
  if (!(times.back() > times.front()))
    throw parameter_error("flange: ensemble: the times must increase (an ensemble runs forward)");
  const simulate_options o = options_of(atol, rtol, dt, max_rhs_evals);
  std::vector<std::string> recorder_names;
  const recorder_set recorders = recorders_of<S>(recorders_in, recorder_names);
  // the cases: each parameter named in `cases` from its array, the others at their defaults
  std::size_t k = 0;
  std::vector<std::pair<std::string, f64>> columns;
  if (!cases_in.is_none()) {
    if (!py::isinstance<py::dict>(cases_in))
      throw parameter_error("flange: ensemble: cases is a dict {parameter name: array of values, one per case}");
    for (auto [name, values] : py::reinterpret_borrow<py::dict>(cases_in)) {
      const std::string n = py::str(name);
      auto a = numbers(values, concat("cases[\"", n, "\"]"));
      if (a.ndim() != 1) throw parameter_error(concat("flange: ensemble: cases[\"", n, "\"] is not 1-D"));
      if (!columns.empty() && std::size_t(a.size()) != k)
        throw parameter_error(concat("flange: ensemble: cases[\"", n, "\"] has ", a.size(), " values, cases[\"",
                                     columns.front().first, "\"] ", k, "; give one value per case"));
      k = std::size_t(a.size());
      columns.emplace_back(n, std::move(a));
    }
  }
  f64 x0s;
  std::size_t x0_rows = 0;
  if (!x0_in.is_none()) {
    x0s = numbers(x0_in, "x0");
    x0_rows = states_shape(x0s, S::n_state, "x0");
    if (x0_rows && columns.empty()) k = x0_rows;
    if (x0_rows && x0_rows != k)
      throw parameter_error(concat("flange: ensemble: x0 has ", x0_rows, " states for ", k, " cases"));
  }
  if (k == 0) throw parameter_error("flange: ensemble: no cases (give cases={name: values} or x0 of shape (k, n))");
  std::vector<P> params(k, P{});
  for (const auto& [n, a] : columns)
    for (std::size_t i = 0; i < k; ++i) set_parameter(params[i], n, a.data()[i]);
  ensemble::case_set<1> cases{{"case"}, {}};
  cases.cases.reserve(k);
  for (std::size_t i = 0; i < k; ++i) cases.cases.push_back({double(i)});

  const std::size_t n_t = times.size();
  std::vector<double> xs(k * n_t * S::n_state, std::numeric_limits<double>::quiet_NaN());
  const double* x0_data = x0_in.is_none() ? nullptr : x0s.data();
  const auto setup = [&](const std::array<double, 1>& c) {
    const auto i = static_cast<std::size_t>(c[0]);
    S s = typename B::factory_type{}(params[i]);
    X x = neutral_state(s);
    if (x0_data) std::copy_n(x0_data + (x0_rows ? i * S::n_state : 0), S::n_state, x.data());
    return std::pair<S, X>{std::move(s), x};
  };
  std::vector<char> ok(k);
  std::vector<std::string> reason(k);
  std::vector<double> fail_time(k), fail_state(k * S::n_state);
  std::vector<long> steps(k), evals(k);
  std::vector<double> recorded(k * max_recorders);
  {
    py::gil_scoped_release free;
    with_method(method, [&](auto m) {
      const auto study =
          ensemble::make_with<decltype(m)>(setup, times.front(), times.back(), o,
                                           ensemble::states_at(times.data(), n_t, xs.data()), recorders);
      const ensemble::run_options ro{.progress_line = ensemble::run_options::show::never};
      const auto collect = [&](auto first, auto last) {
        for (auto it = first; it != last; ++it) {
          const std::size_t i = it->index;
          ok[i] = it->ok;
          reason[i] = it->reason;
          fail_time[i] = it->fail_time;
          std::copy(it->fail_state.begin(), it->fail_state.end(), fail_state.begin() + long(i * S::n_state));
          steps[i] = it->steps;
          evals[i] = it->rhs_evals;
          std::copy(it->values.begin(), it->values.end(), recorded.begin() + long(i * max_recorders));
        }
      };
#ifdef FLANGE_PYTHON_TBB
      if (threads != 1) study.stream(cases, ensemble::tbb_threads{threads}, collect, ro);
      else study.stream(cases, ensemble::serial{}, collect, ro);
#else
      (void)threads;
      study.stream(cases, ensemble::serial{}, collect, ro);
#endif
      return 0;
    });
  }
  // column j of a table of k rows of `width` numbers, as a dict entry per name
  const auto columns_of = [k](const std::vector<std::string>& names, const std::vector<double>& table,
                              std::size_t width) {
    py::dict d;
    for (std::size_t j = 0; j < names.size(); ++j) {
      py::array_t<double> col(static_cast<py::ssize_t>(k));
      for (std::size_t i = 0; i < k; ++i) col.mutable_data()[i] = table[i * width + j];
      d[py::str(names[j])] = col;
    }
    return d;
  };
  const auto names = parameter_names<P>();
  std::vector<double> values;  // each case's parameters, a row a case
  values.reserve(k * names.size());
  for (const auto& p : params)
    for (double v : parameter_values(p)) values.push_back(v);
  const py::dict parameters = columns_of(names, values, names.size());
  const py::dict recorded_d = columns_of(recorder_names, recorded, max_recorders);
  py::array_t<bool> ok_a(static_cast<py::ssize_t>(k));
  for (std::size_t i = 0; i < k; ++i) ok_a.mutable_data()[i] = ok[i] != 0;
  const auto n = py::ssize_t(S::n_state), kk = py::ssize_t(k);
  return classes().ensemble_result(array_of(times), own(std::move(xs), {kk, py::ssize_t(n_t), n}), ok_a, reason,
                                   own(std::move(fail_time), {kk}), own(std::move(fail_state), {kk, n}),
                                   py::array_t<long>(kk, steps.data()), py::array_t<long>(kk, evals.data()),
                                   parameters, recorded_d);
}

}  // namespace detail

/// Binds the scene the factory makes to module m. P: its run-time
/// parameters (python/parameters.hpp), no_parameters for none. The
/// factory must be default-constructible (a lambda without captures).
template <class P, class Factory>
void bind(py::module_& m, Factory) {
  using B = detail::bound<P, Factory>;
  using S = typename B::S;
  detail::load_package();
  py::register_exception_translator(&detail::translate);

  // names and sizes
  m.attr("n_q") = S::n_q;
  m.attr("n_v") = S::n_v;
  m.attr("n_state") = S::n_state;
  py::list joints, state_names;
  py::dict layout;
  for (int c = 0; c < S::n_components; ++c) {
    if (S::tree.q_offset[c] < 0) continue;
    const std::string name(S::table.names[c]);
    joints.append(name);
    py::dict d;
    d["type"] = std::string(S::table.type_names[c]);
    d["q"] = py::slice(S::tree.q_offset[c], S::tree.q_offset[c] + S::table.nq[c], 1);
    d["v"] = py::slice(S::n_q + S::tree.v_offset[c], S::n_q + S::tree.v_offset[c] + S::table.nv[c], 1);
    layout[py::str(name)] = d;
  }
  for (const auto& n : detail::state_names<S>()) state_names.append(n);
  m.attr("joints") = joints;
  m.attr("state_names") = state_names;
  m.attr("joint_layout") = layout;
  py::dict defaults;
  const auto pn = parameter_names<P>();
  const auto pv = parameter_values(P{});
  for (std::size_t i = 0; i < pn.size(); ++i) defaults[py::str(pn[i])] = pv[i];
  m.attr("parameters") = defaults;
  py::list frames;
  for (int c = 0; c < S::n_components; ++c)
    for (int k = 0; k < S::table.nframes[c]; ++k)
      frames.append(detail::concat(S::table.names[c], ".", S::table.frame_names[c][k]));
  m.attr("frames") = frames;

  // the scene at its parameters
  py::class_<B> cls(m, "Scene", "The scene at run-time parameters: Scene(**parameters); the module's functions use Scene().");
  cls.def(py::init([](const py::kwargs& kw) { return std::make_unique<B>(B::params_from(kw)); }))
      .def_property_readonly("parameters", [](const B& b) {
        py::dict d;
        const auto n = parameter_names<P>();
        const auto v = parameter_values(b.params);
        for (std::size_t i = 0; i < n.size(); ++i) d[py::str(n[i])] = v[i];
        return d;
      });
  static B* fallback = nullptr;  // the module's Scene(), for the module functions
  fallback = new B(P{});         // lives as long as the process: the module is never unloaded
  m.attr("scene") = py::cast(fallback, py::return_value_policy::reference);
  const auto at = [](const py::object& params) -> std::unique_ptr<B> {
    if (params.is_none()) return nullptr;
    if (!py::isinstance<py::dict>(params)) throw parameter_error("flange: params is a dict {name: value}");
    return std::make_unique<B>(B::params_from(py::reinterpret_borrow<py::dict>(params)));
  };
  const auto pick = [](const std::unique_ptr<B>& own) -> const B& { return own ? *own : *fallback; };

  cls.def("initial_state", &B::initial_state,
          "The state with the named joints set, every other joint at its neutral configuration, at rest.");
  m.def("initial_state", [](const py::kwargs& kw) { return fallback->initial_state(kw); },
        "The state with the named joints set (initial_state(elbow=0.6, shoulder={\"q\": 0, \"v\": 1})).");

  cls.def("derivative", &B::derivative, py::arg("t"), py::arg("x"), py::arg("out") = py::none(),
          "ẋ = f(t, x) for a state (n_state,) or states (k, n_state).");
  m.def("derivative", [](double t, py::handle x, py::handle out) { return fallback->derivative(t, x, out); },
        py::arg("t"), py::arg("x"), py::arg("out") = py::none(), "ẋ = f(t, x) for a state (n_state,) or states (k, n_state).");

  cls.def("jacobian", &B::jacobian, py::arg("t"), py::arg("x"), "∂ẋ/∂x at (t, x), exact (analytic on trees of one-axis joints and balls, else dual numbers).");
  m.def("jacobian", [at, pick](double t, py::handle x, const py::object& params) { return pick(at(params)).jacobian(t, x); },
        py::arg("t"), py::arg("x"), py::arg("params") = py::none(), "∂ẋ/∂x at (t, x), exact (analytic on trees of one-axis joints and balls, else dual numbers).");

  cls.def("energy", &B::energy, py::arg("x"), py::arg("t") = 0.0, "Kinetic and potential energy at x.");
  m.def("energy", [at, pick](py::handle x, double t, const py::object& params) { return pick(at(params)).energy(x, t); },
        py::arg("x"), py::arg("t") = 0.0, py::arg("params") = py::none(), "Kinetic and potential energy at x.");

  cls.def("momentum", &B::momentum, py::arg("x"), "The linear and angular momentum (world frame, about its origin).");
  m.def("momentum", [at, pick](py::handle x, const py::object& params) { return pick(at(params)).momentum(x); },
        py::arg("x"), py::arg("params") = py::none(), "The linear and angular momentum (world frame, about its origin).");
  cls.def("bodies", &B::bodies, "Every body: name, mass m, centre of mass r_cm (in its frame_a), inertia J.");
  m.def("bodies", [at, pick](const py::object& params) { return pick(at(params)).bodies(); },
        py::arg("params") = py::none(), "Every body: name, mass m, centre of mass r_cm (in its frame_a), inertia J.");

  cls.def("recover", &B::recover, py::arg("t"), py::arg("x"), "Every frame and internal variable at (t, x).");
  m.def("recover", [at, pick](double t, py::handle x, const py::object& params) { return pick(at(params)).recover(t, x); },
        py::arg("t"), py::arg("x"), py::arg("params") = py::none(), "Every frame and internal variable at (t, x).");

  const char* sim_doc = "The states at the requested times (times[0] is x0's), as C++ simulate() returns them.";
  cls.def("simulate", &detail::simulate<B>, py::arg("x0"), py::arg("times"), py::arg("method") = "dopri5",
          py::arg("atol") = 1e-8, py::arg("rtol") = py::none(), py::arg("dt") = 1e-3,
          py::arg("max_rhs_evals") = 100'000'000L, sim_doc);
  m.def("simulate",
        [at, pick](py::handle x0, py::handle times, const std::string& method, double atol, const py::object& rtol,
                   double dt, long max_rhs_evals, const py::object& params) {
          return detail::simulate(pick(at(params)), x0, times, method, atol, rtol, dt, max_rhs_evals);
        },
        py::arg("x0"), py::arg("times"), py::arg("method") = "dopri5", py::arg("atol") = 1e-8,
        py::arg("rtol") = py::none(), py::arg("dt") = 1e-3, py::arg("max_rhs_evals") = 100'000'000L,
        py::arg("params") = py::none(), sim_doc);

  m.def("ensemble", &detail::ensemble<B>, py::arg("cases"), py::arg("times"), py::arg("x0") = py::none(),
        py::arg("recorders") = py::none(), py::arg("method") = "dopri5", py::arg("atol") = 1e-8, py::arg("rtol") = py::none(), py::arg("dt") = 1e-3,
        py::arg("max_rhs_evals") = 10'000'000L, py::arg("threads") = 0,
        "Many runs at run-time parameters (cases: {name: values}), each as simulate() runs it; "
        "failures are recorded per case.");
#ifdef FLANGE_PYTHON_TBB
  m.attr("threaded_ensembles") = true;
#else
  m.attr("threaded_ensembles") = false;
#endif
}

}  // namespace flange::python
