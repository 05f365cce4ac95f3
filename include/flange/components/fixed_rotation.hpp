// FixedRotation: frame_b at a constant offset r from frame_a (frame_a
// coordinates) and turned by a constant rotation R_rel (Modelica's
// FixedRotation). R_rel is in the paper's convention: it rotates frame_a
// coordinates into frame_b's.
//
//   r₂ = r₁ + R₁'·r          F₂ = −R_rel·F₁
//   R₂ = R_rel·R₁            M₂ = −R_rel·(M₁ − r × F₁)
//
// Frames 1, 2 are frame_a, frame_b. A rigid edge of the kinematic tree. The
// rotation is given as an orientation (math/rotation.hpp: axis–angle,
// Cardan angles, roll–pitch–yaw or a matrix, checked orthogonal), or with
// FixedRotation<"r", axis::z> as an angle about a coordinate axis, which
// keeps a planar scene planar. A scene without one pays nothing for it: the
// frames of a link share its orientation unless a FixedRotation turns them.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"
#include "flange/joints/axis.hpp"
#include "flange/math/rotation.hpp"

namespace flange {

namespace detail {
template <class Axis>
struct fixed_rotation_params {
  Vec3d r = Vec3d::Zero();  ///< frame_b's origin, frame_a coordinates
  orientation R;            ///< frame_b's orientation relative to frame_a
};
template <int I>
struct fixed_rotation_params<axis::coordinate<I>> {
  Vec3d r = Vec3d::Zero();  ///< frame_b's origin, frame_a coordinates
  double angle = 0;         ///< frame_b turned by this angle about the axis [rad]
};
}  // namespace detail

template <fixed_string Name, class Axis = axis::any>
class FixedRotation {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "FixedRotation";
  static constexpr role kind = role::rigid;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 0> internals{};

  using params = detail::fixed_rotation_params<Axis>;
  explicit FixedRotation(params p) : offset_(p.r) {
    detail::require_finite(name.view(), type_name, "r", offset_);
    if constexpr (Axis::fixed) {
      detail::require_finite(name.view(), type_name, "angle", p.angle);
      rotation_ = axis_rotation<double>(Axis::unit(), p.angle);
    } else {
      detail::require_rotation(name.view(), type_name, "R", p.R.R);
      rotation_ = p.R.R;
    }
  }

  [[nodiscard]] const Vec3d& r() const { return offset_; }
  [[nodiscard]] const Mat3d& R_rel() const { return rotation_; }

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> r{offset_, "r"};
    const param<Mat3d> R{rotation_, "R_rel"};
    return boost::hana::make_tuple(eq(r_<1>, r_<0> + transpose(R_<0>) * r),  //
                                   orientation_eq(R_<1>, R * R_<0>),         //
                                   eq(F_<1>, -(R * F_<0>)),                   //
                                   eq(M_<1>, -(R * (M_<0> - cross(r, F_<0>)))));
  }

  /// A rigid edge of the kinematic tree: frame_b's constant pose in frame_a.
  /// It turns the frames behind it about a coordinate axis (rotation_axis k)
  /// or about any axis (−1).
  static constexpr int rotation_axis = Axis::fixed ? Axis::index : -1;
  template <class T>
  [[nodiscard]] pose<T> relative_pose() const {
    return {rotation_.cast<T>(), offset_.cast<T>()};
  }

 private:
  Vec3d offset_;
  Mat3d rotation_;
};

}  // namespace flange
