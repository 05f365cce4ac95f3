// World: the inertial frame, and the gravity acceleration g for every Body.
//
//   r₁ = 0            R₁ = 1
//
// One frame, frame_b (as in Modelica). Its cut force and torque are whatever
// the rest of the scene needs: the world holds the mechanism up.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"

namespace flange {

namespace gravity_kind {
struct uniform {};  ///< g is a run-time vector (default (0, −9.81, 0))
struct none {};     ///< no gravity at all: no gravity arithmetic is generated
}  // namespace gravity_kind

template <fixed_string Name = "world", class Gravity = gravity_kind::uniform>
class World {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "World";
  static constexpr role kind = role::world;
  static constexpr std::array<std::string_view, 1> frames{"frame_b"};
  static constexpr std::array<internal_decl, 0> internals{};
  static constexpr bool has_gravity = std::is_same_v<Gravity, gravity_kind::uniform>;

  struct params {
    Vec3d g = Vec3d(0, -9.81, 0);
  };

  World() : World(params{}) {}
  explicit World(params p) : g_(has_gravity ? p.g : Vec3d::Zero()) {
    detail::require_finite(name.view(), "World", "g (gravity)", g_);
  }

  [[nodiscard]] const Vec3d& g() const { return g_; }

  [[nodiscard]] auto equations() const {
    using namespace expr;
    return boost::hana::make_tuple(eq(r_<0>, zero<shape::vec>{}),  //
                                   orientation_eq(R_<0>, identity{}));
  }

 private:
  Vec3d g_;
};

}  // namespace flange
