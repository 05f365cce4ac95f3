// FixedTranslation: two frames a constant vector d apart (d in frame_a).
//
//   r₂ = r₁ + R₁'·d          F₂ = −F₁
//   R₂ = R₁                  M₂ = −M₁ + d × F₁
//
// Frames 1, 2 are frame_a, frame_b. A rigid edge of the kinematic tree.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/core/component.hpp"
#include "flange/core/joint.hpp"

namespace flange {

template <fixed_string Name>
class FixedTranslation {
 public:
  static constexpr auto name = Name;
  static constexpr std::string_view type_name = "FixedTranslation";
  static constexpr role kind = role::rigid;
  static constexpr std::array<std::string_view, 2> frames{"frame_a", "frame_b"};
  static constexpr std::array<internal_decl, 0> internals{};

  struct params {
    Vec3d d;
  };
  explicit FixedTranslation(params p) : d_(p.d) { detail::require_finite(name.view(), "FixedTranslation", "d", d_); }

  /// frame_b's origin seen from frame_a, in frame_a coordinates.
  [[nodiscard]] const Vec3d& d() const { return d_; }

  [[nodiscard]] auto equations() const {
    using namespace expr;
    const param<Vec3d> d{d_, "d"};
    return boost::hana::make_tuple(eq(r_<1>, r_<0> + transpose(R_<0>) * d),  //
                                   orientation_eq(R_<1>, R_<0>),             //
                                   eq(F_<1>, -F_<0>),                         //
                                   eq(M_<1>, -M_<0> + cross(d, F_<0>)));
  }

  /// A rigid edge of the kinematic tree: frame_b's constant pose in frame_a.
  /// It does not rotate (rotation_axis −2: none), so frames it joins share
  /// their orientation and no rotation arithmetic is generated for them.
  static constexpr int rotation_axis = -2;
  template <class T>
  [[nodiscard]] pose<T> relative_pose() const {
    return {Mat3<T>::Identity(), d_.cast<T>()};
  }

 private:
  Vec3d d_;
};

}  // namespace flange
