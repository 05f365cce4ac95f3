// always_false<T...>: a false that depends on template arguments, so a
// static_assert in a discarded branch fires only when that branch is taken.
#pragma once

namespace flange {

template <class... T>
inline constexpr bool always_false = false;

}  // namespace flange
