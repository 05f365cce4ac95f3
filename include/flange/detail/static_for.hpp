// static_for<N>(f): f(integral_constant<int, 0>) … f(integral_constant<int, N−1>),
// unrolled, so that each call sees its index as a constant expression.
#pragma once
#include <type_traits>
#include <utility>

#include "flange/detail/inline.hpp"

namespace flange::detail {

template <int N, class F>
FLANGE_INLINE void static_for(F&& f) {
  [&]<int... I>(std::integer_sequence<int, I...>) FLANGE_INLINE_LAMBDA {
    (f(std::integral_constant<int, I>{}), ...);
  }(std::make_integer_sequence<int, N>{});
}

}  // namespace flange::detail
