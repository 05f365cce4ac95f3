// A scene's run-time parameters as named numbers, for a Python module
// (python/module.hpp): a struct adapted to Boost.Hana whose members are
// numbers or such structs, flattened to names "member" and "member.sub".
//
//   struct crane_params { double kp = 10, m_load = 0.5; };
//   BOOST_HANA_ADAPT_STRUCT(crane_params, kp, m_load);     // at namespace scope
//   auto make_crane(const crane_params& p) { return flange::scene(…p.kp…); }
//
// The defaults are the struct's own (P{}); a scene without run-time
// parameters uses no_parameters.
#pragma once
#include <boost/hana/accessors.hpp>
#include <boost/hana/concept/struct.hpp>
#include <boost/hana/first.hpp>
#include <boost/hana/for_each.hpp>
#include <boost/hana/second.hpp>
#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "flange/detail/always_false.hpp"
#include "flange/detail/closest_name.hpp"
#include "flange/errors.hpp"

namespace flange::python {

/// A name the scene does not have (a parameter, a joint, a field of a
/// joint's state): raised in Python as flange.UnknownNameError, a KeyError.
struct unknown_name : parameter_error {
  using parameter_error::parameter_error;
};

/// The parameters of a scene that has none.
struct no_parameters {};

namespace detail {
using flange::detail::concat;

/// f(name, member) for every number in p, nested structs' members named
/// "outer.inner", in declaration order.
template <class P, class F>
void for_each_parameter(P& p, const std::string& prefix, F&& f) {
  using Plain = std::remove_const_t<P>;
  if constexpr (boost::hana::Struct<Plain>::value) {
    boost::hana::for_each(boost::hana::accessors<Plain>(), [&](auto pair) {
      std::string name = prefix + boost::hana::to<const char*>(boost::hana::first(pair));
      auto& m = boost::hana::second(pair)(p);
      using M = std::remove_cvref_t<decltype(m)>;
      if constexpr (std::is_arithmetic_v<M>) f(name, m);
      else if constexpr (boost::hana::Struct<M>::value) for_each_parameter(m, name + ".", f);
      else
        static_assert(flange::always_false<M>,
                      "flange::python: a member of the scene's parameter struct is neither a number nor a struct "
                      "adapted to Boost.Hana (BOOST_HANA_ADAPT_STRUCT(type, members...))");
    });
  } else {
    static_assert(std::is_same_v<Plain, no_parameters>,
                  "flange::python: a scene's parameters are a struct adapted to Boost.Hana "
                  "(BOOST_HANA_ADAPT_STRUCT(type, members...) at namespace scope), or no_parameters");
  }
}
}  // namespace detail

/// The parameters' names, in order.
template <class P>
std::vector<std::string> parameter_names() {
  std::vector<std::string> names;
  const P p{};
  detail::for_each_parameter(p, "", [&](const std::string& n, const auto&) { names.push_back(n); });
  return names;
}

/// The parameters' values, in the order of parameter_names.
template <class P>
std::vector<double> parameter_values(const P& p) {
  std::vector<double> v;
  detail::for_each_parameter(p, "", [&](const std::string&, const auto& m) { v.push_back(static_cast<double>(m)); });
  return v;
}

/// Sets the parameter `name`; throws parameter_error naming the closest
/// name for a name it does not have, and the value for one its type cannot
/// hold (a fraction for a whole number, a non-finite value).
template <class P>
void set_parameter(P& p, std::string_view name, double value) {
  bool found = false;
  detail::for_each_parameter(p, "", [&](const std::string& n, auto& m) {
    if (n != name) return;
    found = true;
    using M = std::remove_cvref_t<decltype(m)>;
    if (!std::isfinite(value))
      throw parameter_error(detail::concat("flange: parameter \"", name, "\" = ", value, " is not finite"));
    if constexpr (std::is_same_v<M, bool>) {
      if (value != 0 && value != 1)
        throw parameter_error(detail::concat("flange: parameter \"", name, "\" is a flag (0 or 1), not ", value));
      m = value != 0;
    } else if constexpr (std::is_integral_v<M>) {
      if (value != std::trunc(value))
        throw parameter_error(detail::concat("flange: parameter \"", name, "\" is a whole number, not ", value));
      m = static_cast<M>(value);
    } else {
      m = static_cast<M>(value);
    }
  });
  if (!found) {
    const auto names = parameter_names<P>();
    if (names.empty())
      throw unknown_name(detail::concat("flange: the scene has no run-time parameters; \"", name, "\" was given"));
    throw unknown_name(detail::concat("flange: the scene has no parameter \"", name, "\"; did you mean \"",
                                         names[flange::detail::closest_name(name, names)], "\"?"));
  }
}

}  // namespace flange::python
