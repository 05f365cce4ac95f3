// A list of types, and its I-th element.
#pragma once
#include <tuple>

namespace flange::detail {

template <class...>
struct type_list {};

template <int I, class... Ts>
using nth_t = std::tuple_element_t<I, std::tuple<Ts...>>;

}  // namespace flange::detail
