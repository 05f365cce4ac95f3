// Axis frames: a link behind a joint whose axis is given at run time
// (Revolute<"j">({.n = …})) computes in coordinates turned so that the axis
// is z.
//
// A run-time axis makes the joint's motion subspace a dense vector: every
// projection on it (U = I_A·S, D = Sᵀ·U, u = τ − Sᵀ·p_A, q̈'s share of the
// acceleration) is a dot product, and its rotation is built from n by
// Rodrigues' formula at every evaluation. In a frame whose z axis is n the
// same joint is a joint about z (core/joint.hpp, motion_in_axis_frame):
// S = ±e_z picks a column, and its rotation is a (cos, sin) pair. The frame
// is a constant rotation A_L of the link's coordinates with rows x, y, n,
// chosen at construction (dynamics/model.hpp):
//
//   link coordinates  = A_L · (the joint's child-side frame's coordinates)
//   the link's motion   E = R_z(q) · C_L,  C_L = A_L · R_s
//
// with R_s the rotation of the frame the joint hangs on, in its parent link's
// (possibly turned) coordinates. Every constant the algorithms keep in link
// coordinates (the bodies' inertia, the frames' offsets and rotations) is
// stored turned, so nothing else changes: a frame's pose is its set's pose
// in its link, turn included, and the outputs (recover, the residual) are
// those of the untouched scene.
//
// A link is turned only where it costs nothing elsewhere: its joint offers an
// axis frame, and every joint hanging from the link already turns its own
// child by a general rotation (a run-time axis, or a FixedRotation on the
// way), since the turn makes every frame of the link a general rotation of
// it. A typed joint (axis::z) below keeps its 2-D arithmetic.
#pragma once
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "flange/core/joint.hpp"
#include "flange/detail/lazy.hpp"
#include "flange/math/rotation.hpp"
#include "flange/math/types.hpp"

namespace flange::detail {

template <class S>
struct axis_frames {
  static constexpr int NL = S::tree.n_links;

  /// Whether link L's own rotation (its joint's, with the rotation of the
  /// frame it hangs on) is already a general 3 × 3 one without a turn.
  template <int L>
  static constexpr bool general_without_turn() {
    constexpr auto& tree = S::tree;
    using J = typename S::template component_type<tree.link_joint[L]>;
    constexpr int dir = tree.link_dir[L] > 0 ? 1 : -1;
    using E = decltype(std::declval<const J&>().template motion<double, dir, true>(static_cast<const double*>(nullptr)).E);
    return axis_framed_joint<J> || std::is_same_v<std::remove_cvref_t<E>, Mat3d> ||
           tree.set_rotation[tree.link_parent_set[L]] == -1;
  }
  template <int L>
  static constexpr bool offers() {
    return axis_framed_joint<typename S::template component_type<S::tree.link_joint[L]>>;
  }

  static constexpr std::array<bool, NL> turned = [] {
    std::array<bool, NL> offer{}, general{}, r{};
    [&]<int... L>(std::integer_sequence<int, L...>) {
      ((offer[L + 1] = offers<L + 1>(), general[L + 1] = general_without_turn<L + 1>()), ...);
    }(std::make_integer_sequence<int, NL - 1>{});
    for (int L = 1; L < NL; ++L) {
      bool ok = offer[L];
      for (int C = 1; C < NL; ++C)
        if (S::tree.link_parent[C] == L && !general[C]) ok = false;
      r[L] = ok;
    }
    return r;
  }();
  /// Whether link L is its parent's aligned child: both turned, and L the
  /// first turned child. The parent's x axis is then chosen normal to both
  /// axes, and L's turn C_L is R_z(θ₀)·R_x(α): E = R_z(q + θ₀)·R_x(α), two
  /// (c, s) pairs instead of a 3 × 3 matrix (model.hpp).
  static constexpr std::array<bool, NL> aligned = [] {
    std::array<bool, NL> r{}, taken{};
    for (int L = 1; L < NL; ++L) {
      const int P = S::tree.link_parent[L];
      if (turned[L] && P > 0 && turned[P] && !taken[P]) r[L] = taken[P] = true;
    }
    return r;
  }();
  static constexpr bool any = [] {
    for (const bool t : turned)
      if (t) return true;
    return false;
  }();
};

/// Whether link L computes in its joint's axis frame.
template <class S, int L>
inline constexpr bool axis_framed = axis_frames<S>::turned[L];
/// Whether its turn is R_z(θ₀)·R_x(α) (axis_frames::aligned).
template <class S, int L>
inline constexpr bool axis_aligned = axis_frames<S>::aligned[L];

/// An aligned link's turn: R_x(α) as (cos α, sin α), and θ₀.
struct axis_alignment {
  double c = 1, s = 0, offset = 0;
};

/// The kind of a connection set's rotation relative to its link's
/// coordinates: −2 none, k about coordinate axis k, −1 any. Every set of a
/// turned link is turned against it.
template <class S>
constexpr int set_rotation_kind(int set) {
  const int L = S::tree.set_link[set];
  return L > 0 && axis_frames<S>::turned[L] ? -1 : S::tree.set_rotation[set];
}

/// A_L for a unit axis n: a rotation with rows x, y, n (A_L·n = e_z), and x
/// normal to m (the aligned child's axis) where the two axes are not
/// parallel.
FLANGE_LAZY
Mat3d axis_frame_rotation(const Vec3d& n, const Vec3d& m = Vec3d::Zero()) {
  Vec3d e1, e2;
  complete_basis(n, e1, e2);
  const Vec3d nm = n.cross(m);
  const Vec3d x = nm.norm() > 1e-9 ? Vec3d(nm.normalized()) : e1;
  Mat3d A;
  A.row(0) = x.transpose();
  A.row(1) = n.cross(x).transpose();
  A.row(2) = n.transpose();
  return A;
}
FLANGE_COMMON(Mat3d axis_frame_rotation<0>(const Vec3d&, const Vec3d&))

}  // namespace flange::detail
