// FixedTranslation: two frames a constant vector d apart (d in frame_a).
//
//   r₂ = r₁ + R₁'·d          F₂ = −F₁
//   R₂ = R₁                  M₂ = −M₁ + d × F₁
//
// Frames 1, 2 are frame_a, frame_b. A rigid edge of the kinematic tree.
#pragma once
#include <boost/hana/tuple.hpp>

#include "flange/components/component.hpp"
#include "flange/components/frame_kinematics.hpp"

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

  /// The flows at frame_a from those at frame_b, and the reverse: the
  /// component's own equations solved for the other side.
  template <class T>
  [[nodiscard]] wrench<T> flows_a_from_b(const wrench<T>& b, const T&) const {
    const Vec3<T> Fa = -b.f;
    return {Fa, d_.cast<T>().cross(Fa) - b.n};
  }
  template <class T>
  [[nodiscard]] wrench<T> flows_b_from_a(const wrench<T>& a, const T&) const {
    return {-a.f, -a.n + d_.cast<T>().cross(a.f)};
  }

 private:
  Vec3d d_;
};

}  // namespace flange
