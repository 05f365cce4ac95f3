// A connection is a type naming two frames, "component.frame":
//
//     flange::connect<"world.frame_b", "joint.frame_a">
//
// as Modelica's connect(world.frame_b, joint.frame_a).
#pragma once
#include <string_view>

#include "flange/detail/fixed_string.hpp"

namespace flange {

template <fixed_string A, fixed_string B>
struct connection {
  static constexpr std::string_view a = A.view();
  static constexpr std::string_view b = B.view();
};

template <fixed_string A, fixed_string B>
inline constexpr connection<A, B> connect{};

template <class T>
struct is_connection : std::false_type {};
template <fixed_string A, fixed_string B>
struct is_connection<connection<A, B>> : std::true_type {};

}  // namespace flange
