// Contact geometry: the shapes a Contact pairs, and for each supported pair
// where they overlap. A pair has a fixed number of candidate points (one for
// a sphere, two for a capsule's ends, eight for a box's corners); each
// candidate is a sphere of some radius on shape a, with the normal N from b
// toward it, its overlap with b along N, and the point of b's surface under
// it. The contact law (contact.hpp) turns each overlap into a force.
//
//   sphere      a sphere centred on its frame's origin (a point: a small one)
//   half_space  {p : n·p ≤ offset}, p in its frame's coordinates
//   box         a box of half extents h about `center`, its axes the rows of
//               `axes` (frame coordinates), its edges rounded by
//               corner_radius ρ: the set of points within ρ of the inner
//               box of half extents h − ρ
//   capsule     the points within `radius` of the segment center ± half_length·axis
//
// Pairs (shape a at frame_a, shape b at frame_b):
//   sphere–half_space, sphere–sphere, sphere–box  one point
//   capsule–half_space                            two: the ends' spheres
//   box–half_space                                eight: the corners' spheres of radius ρ
// A pair against a half-space also gives each point's sphere centre in
// frame_a coordinates (center(i)), so that a half-space at rest in the World
// can be met in the coordinates of frame_a's link (contact.hpp).
//
// Against a half-space a box touches with its corners' spheres, so a face
// resting on the ground stands on its four corners; a capsule lying on the
// ground touches with both ends. A sphere against a box meets the rounded
// box's surface: the effective radius is the sphere's (a face's), also at
// edges and corners.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <type_traits>

#include "flange/components/body_shape.hpp"
#include "flange/core/component.hpp"
#include "flange/core/frame_kinematics.hpp"
#include "flange/detail/inline.hpp"
#include "flange/detail/lazy.hpp"

namespace flange {

/// The shapes a Contact pairs.
namespace contact_shape {
/// A sphere centred on its frame's origin (a point is a small sphere).
struct sphere {
  double radius = 0;  ///< [m], positive (to be given)
};
/// The half-space {p : n·p ≤ offset}, p in its frame's coordinates.
struct half_space {
  Vec3d n = Vec3d::UnitZ();  ///< outward unit normal
  double offset = 0;         ///< [m]
};
/// A box with rounded edges, about `center` with its axes the rows of `axes`.
struct box {
  Vec3d half_extents = Vec3d::Zero();         ///< h [m], along the box's own axes (to be given)
  Vec3d center = Vec3d::Zero();                ///< [m], frame coordinates
  Mat3d axes = Mat3d::Identity();              ///< rows: the box's axes in frame coordinates (a rotation)
  double corner_radius = 1e-3;                 ///< ρ [m], 0 < ρ ≤ min(h): the corners' and edges' rounding
};
/// The points within `radius` of the segment center ± half_length·axis.
struct capsule {
  double radius = 0;              ///< [m], positive (to be given)
  double half_length = 0;         ///< [m], half the segment between the end spheres' centres
  Vec3d center = Vec3d::Zero();   ///< [m], frame coordinates
  Vec3d axis = Vec3d::UnitZ();    ///< unit, frame coordinates
};

/// A BodyBox's box as contact geometry, at the BodyBox's frame_a:
/// .a = contact_shape::box_of(crate) (its edges rounded by corner_radius,
/// at most its smallest half extent).
template <fixed_string N>
[[nodiscard]] box box_of(const BodyShape<N, shape_kind::box>& b, double corner_radius = 1e-3) {
  const Vec3d h = b.size() / 2;
  return {.half_extents = h, .center = b.r() / 2, .axes = b.axes(), .corner_radius = std::min(corner_radius, h.minCoeff())};
}
/// A BodyCylinder's cylinder as a capsule at its frame_a, of its outer
/// radius and its overall length (the caps' ends at its end faces' centres,
/// so that it rests on its side as the cylinder does; stood on an end it
/// balances on a cap): .a = contact_shape::capsule_of(roller).
template <fixed_string N>
[[nodiscard]] capsule capsule_of(const BodyShape<N, shape_kind::cylinder>& c) {
  const double r = c.size().y() / 2, l = c.size().x();
  return {.radius = r, .half_length = std::max(0.0, l / 2 - r), .center = c.r() / 2, .axis = c.axes().row(0).transpose()};
}
}  // namespace contact_shape

namespace detail {

/// One candidate point of a pair: the sphere's centre c on shape a, its
/// radius, the unit normal N from b toward it, and its overlap with b.
template <class T>
struct contact_overlap {
  Vec3<T> N = Vec3<T>::UnitZ();
  T depth{0};                        ///< > 0 where the shapes overlap
  Vec3<T> surface = Vec3<T>::Zero(); ///< the point of b's surface nearest c (world)
};

/// Throws a parameter_error for shape `which` of a Contact when `ok` is false.
inline void require_shape(bool ok, std::string_view name, std::string_view which, const auto&... what) {
  if (!ok) throw parameter_error(concat("Contact \"", name, "\": ", which, what...));
}

/// Hertz's force grows with the radius: a point (radius 0) would push with none.
FLANGE_LAZY
void check_radius(std::string_view name, std::string_view which, double r) {
  require_finite(name, "Contact", which, r);
  require_shape(r > 0, name, which, " = ", r, " must be positive (a point is a small sphere: Hertz's force vanishes with the radius)");
}
FLANGE_COMMON(void check_radius<0>(std::string_view, std::string_view, double))

FLANGE_LAZY
void check_unit(std::string_view name, std::string_view which, const Vec3d& n) {
  require_finite(name, "Contact", which, n);
  require_shape(std::abs(n.norm() - 1) <= 1e-9, name, which, " = [", n.transpose(), "] is not a unit vector (norm ",
                n.norm(), ")");
}
FLANGE_COMMON(void check_unit<0>(std::string_view, std::string_view, const Vec3d&))

FLANGE_LAZY
void check_shape(std::string_view name, std::string_view which, const contact_shape::sphere& s) {
  check_radius(name, concat(which, ".radius"), s.radius);
}
FLANGE_COMMON(void check_shape<0>(std::string_view, std::string_view, const contact_shape::sphere&))
FLANGE_LAZY
void check_shape(std::string_view name, std::string_view which, const contact_shape::half_space& s) {
  require_finite(name, "Contact", concat(which, ".offset"), s.offset);
  check_unit(name, concat(which, ".n"), s.n);
}
FLANGE_COMMON(void check_shape<0>(std::string_view, std::string_view, const contact_shape::half_space&))
FLANGE_LAZY
void check_shape(std::string_view name, std::string_view which, const contact_shape::box& s) {
  require_finite(name, "Contact", concat(which, ".half_extents"), s.half_extents);
  require_finite(name, "Contact", concat(which, ".center"), s.center);
  require_finite(name, "Contact", concat(which, ".axes"), s.axes);
  require_shape(s.half_extents.minCoeff() > 0, name, which, ".half_extents = [", s.half_extents.transpose(),
                "] must be positive");
  require_rotation(name, "Contact", concat(which, ".axes"), s.axes);
  check_radius(name, concat(which, ".corner_radius"), s.corner_radius);
  require_shape(s.corner_radius <= s.half_extents.minCoeff(), name, which, ".corner_radius = ", s.corner_radius,
                " exceeds the smallest half extent ", s.half_extents.minCoeff());
}
FLANGE_COMMON(void check_shape<0>(std::string_view, std::string_view, const contact_shape::box&))
FLANGE_LAZY
void check_shape(std::string_view name, std::string_view which, const contact_shape::capsule& s) {
  check_radius(name, concat(which, ".radius"), s.radius);
  require_finite(name, "Contact", concat(which, ".half_length"), s.half_length);
  require_shape(s.half_length >= 0, name, which, ".half_length = ", s.half_length, " is negative");
  require_finite(name, "Contact", concat(which, ".center"), s.center);
  check_unit(name, concat(which, ".axis"), s.axis);
}
FLANGE_COMMON(void check_shape<0>(std::string_view, std::string_view, const contact_shape::capsule&))

/// Overlap of a sphere (centre c, radius r, world) with the half-space s at frame b.
template <class T>
FLANGE_INLINE contact_overlap<T> sphere_half_space(const Vec3<T>& c, double r, const contact_shape::half_space& s,
                                     const frame_kinematics<T>& b) {
  contact_overlap<T> o;
  o.N = b.R.transpose() * s.n.template cast<T>();
  const T gap = o.N.dot(c - b.r) - T(s.offset);
  o.depth = T(r) - gap;
  o.surface = c - gap * o.N;
  return o;
}

/// The geometry of the pair (A at frame_a, B at frame_b): its points, each
/// point's effective radius, the size of its smaller shape (a sphere's or a
/// capsule's radius, a box's smallest half extent), and each point's
/// overlap. The primary template is a pair that is not supported.
template <class A, class B>
struct contact_pair {
  static constexpr bool supported = false;
};

template <>
struct contact_pair<contact_shape::sphere, contact_shape::half_space> {
  static constexpr bool supported = true;
  static constexpr int points = 1;
  contact_shape::sphere a;
  contact_shape::half_space b;
  [[nodiscard]] double radius(int) const { return a.radius; }
  [[nodiscard]] double size() const { return a.radius; }
  [[nodiscard]] Vec3d center(int) const { return Vec3d::Zero(); }
  template <class T>
  [[nodiscard]] FLANGE_INLINE contact_overlap<T> overlap(int, const frame_kinematics<T>& ka, const frame_kinematics<T>& kb) const {
    return sphere_half_space(ka.r, a.radius, b, kb);
  }
};

template <>
struct contact_pair<contact_shape::sphere, contact_shape::sphere> {
  static constexpr bool supported = true;
  static constexpr int points = 1;
  contact_shape::sphere a, b;
  [[nodiscard]] double radius(int) const { return a.radius * b.radius / (a.radius + b.radius); }
  [[nodiscard]] double size() const { return std::min(a.radius, b.radius); }
  template <class T>
  [[nodiscard]] FLANGE_INLINE contact_overlap<T> overlap(int, const frame_kinematics<T>& ka, const frame_kinematics<T>& kb) const {
    using std::sqrt;
    contact_overlap<T> o;
    const Vec3<T> d = ka.r - kb.r;
    const T dist = sqrt(d.squaredNorm());
    if (!(dist > T(0))) return o;  // concentric: no direction (Simbody likewise applies nothing)
    o.N = d / dist;
    o.depth = T(a.radius + b.radius) - dist;
    o.surface = kb.r + T(b.radius) * o.N;
    return o;
  }
};

template <>
struct contact_pair<contact_shape::capsule, contact_shape::half_space> {
  static constexpr bool supported = true;
  static constexpr int points = 2;
  contact_shape::capsule a;
  contact_shape::half_space b;
  [[nodiscard]] double radius(int) const { return a.radius; }
  [[nodiscard]] double size() const { return a.radius; }
  /// End i's sphere centre in frame_a: i = 0 at −half_length along the axis.
  [[nodiscard]] Vec3d center(int i) const { return a.center + (i == 0 ? -a.half_length : a.half_length) * a.axis; }
  template <class T>
  [[nodiscard]] FLANGE_INLINE contact_overlap<T> overlap(int i, const frame_kinematics<T>& ka, const frame_kinematics<T>& kb) const {
    return sphere_half_space(Vec3<T>(ka.r + ka.R.transpose() * center(i).template cast<T>()), a.radius, b, kb);
  }
};

template <>
struct contact_pair<contact_shape::box, contact_shape::half_space> {
  static constexpr bool supported = true;
  static constexpr int points = 8;
  contact_shape::box a;
  contact_shape::half_space b;
  /// Corner i's sphere centre in frame_a: bit 0, 1, 2 of i give the sign
  /// (clear −, set +) along the box's first, second, third axis.
  [[nodiscard]] Vec3d center(int i) const {
    const Vec3d h = a.half_extents - Vec3d::Constant(a.corner_radius);
    const Vec3d s((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    return a.center + a.axes.transpose() * s;
  }
  [[nodiscard]] double radius(int) const { return a.corner_radius; }
  [[nodiscard]] double size() const { return a.half_extents.minCoeff(); }
  template <class T>
  [[nodiscard]] FLANGE_INLINE contact_overlap<T> overlap(int i, const frame_kinematics<T>& ka, const frame_kinematics<T>& kb) const {
    return sphere_half_space(Vec3<T>(ka.r + ka.R.transpose() * center(i).template cast<T>()), a.corner_radius, b, kb);
  }
};

template <>
struct contact_pair<contact_shape::sphere, contact_shape::box> {
  static constexpr bool supported = true;
  static constexpr int points = 1;
  contact_shape::sphere a;
  contact_shape::box b;
  [[nodiscard]] double radius(int) const { return a.radius; }
  [[nodiscard]] double size() const { return std::min(a.radius, b.half_extents.minCoeff()); }
  template <class T>
  [[nodiscard]] FLANGE_INLINE contact_overlap<T> overlap(int, const frame_kinematics<T>& ka, const frame_kinematics<T>& kb) const {
    using std::abs;
    using std::sqrt;
    contact_overlap<T> o;
    // The sphere's centre in the box's coordinates, and the inner box (h − ρ).
    const Mat3<T> to_box = b.axes.template cast<T>() * kb.R;
    const Vec3<T> p = to_box * (ka.r - kb.r) - b.axes.template cast<T>() * b.center.template cast<T>();
    const Vec3d h = b.half_extents - Vec3d::Constant(b.corner_radius);
    Vec3<T> q;  // the inner box's point nearest p
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      q[k] = p[k] > T(h[k]) ? T(h[k]) : p[k] < T(-h[k]) ? T(-h[k]) : p[k];
      if (q[k] != p[k]) inside = false;
    }
    Vec3<T> n;  // outward normal, box coordinates
    T distance;  // signed distance of p from the inner box
    if (!inside) {
      const Vec3<T> d = p - q;
      distance = sqrt(d.squaredNorm());
      n = d / distance;
    } else {
      // Inside the inner box: out through the nearest face.
      int k = 0;
      T least = T(h[0]) - abs(p[0]);
      for (int j = 1; j < 3; ++j) {
        const T room = T(h[j]) - abs(p[j]);
        if (room < least) least = room, k = j;
      }
      n = Vec3<T>::Zero();
      n[k] = p[k] < T(0) ? T(-1) : T(1);
      q[k] = n[k] * T(h[k]);
      distance = -least;
    }
    const Mat3<T> from_box = to_box.transpose();
    o.N = from_box * n;
    o.depth = T(a.radius + b.corner_radius) - distance;
    o.surface = kb.r + kb.R.transpose() * b.center.template cast<T>() + from_box * (q + T(b.corner_radius) * n);
    return o;
  }
};

template <class A, class B>
void check_pair(std::string_view name, const contact_pair<A, B>& g) {
  check_shape(name, "a", g.a);
  check_shape(name, "b", g.b);
}

}  // namespace detail
}  // namespace flange
