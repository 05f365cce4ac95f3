// Eᵀ·X·E for a 3 × 3 block X and a rotation E of any of sparse.hpp's types:
// how an inertia's blocks, kept in a child's coordinates, are turned into its
// parent's (the composite inertias of mass_matrix.hpp, the articulated
// inertias of articulated_body.hpp).
//
// A coordinate rotation is applied column by column as (c, s) pairs; a general
// one as two written-out products (small_matrix.hpp), of which the second
// needs only its upper triangle when X is symmetric (Θ, M, a rotational
// inertia): 45 products instead of 54; or, where that measures faster (the
// mass matrix), as rotations of its columns and rows.
#pragma once
#include <type_traits>

#include "flange/detail/inline.hpp"
#include "flange/detail/static_for.hpp"
#include "flange/math/small_matrix.hpp"
#include "flange/math/sparse.hpp"

namespace flange {

/// The row (and column) Z a rotation of type E leaves zero when it was (−1:
/// none): Z itself for a rotation about axis Z, else none.
template <class E>
constexpr int keeps_zero(int Z) {
  if constexpr (requires { std::remove_cvref_t<E>::axis; }) return std::remove_cvref_t<E>::axis == Z ? Z : -1;
  else return -1;
}

/// Eᵀ·X·E for any 3 × 3 X; ZR (−1: none) a row X is known to have zero.
/// A coordinate rotation about axis ZR keeps that row zero and turns only the
/// other two (an articulated inertia's H behind a revolute joint,
/// articulated_body.hpp).
template <class T, int ZR = -1, class E>
FLANGE_INLINE Mat3<T> rotated_back(const E& R, const Mat3<T>& X) {
  if constexpr (is_identity_rotation<E>) {
    return X;
  } else if constexpr (std::is_same_v<std::remove_cvref_t<E>, Mat3<T>>) {
    return small::mul(small::mul_tn(R, X), R);
  } else if constexpr (is_rotation_product<E>) {
    // (A·B)ᵀ·X·(A·B) = Bᵀ·(Aᵀ·X·A)·B; A about axis ZR leaves row ZR zero for B.
    return rotated_back<T, keeps_zero<decltype(R.a)>(ZR)>(R.b, rotated_back<T, ZR>(R.a, X));
  } else {
    // A = Eᵀ·X column by column (the rows X may hold: CM), then B = A·E
    // row by row, the rows A may hold (AM) only.
    constexpr int CM = ZR < 0 ? 7 : 7 & ~(1 << ZR), AM = detail::axis_rotation_mask(E::axis, CM);
    Mat3<T> A, B;
    detail::static_for<3>([&](auto k) FLANGE_INLINE_LAMBDA {
      constexpr int K = decltype(k)::value;
      const auto c = rot_t(R, to_svec<CM>(Vec3<T>(X(0, K), X(1, K), X(2, K))));
      detail::static_for<3>([&](auto i) FLANGE_INLINE_LAMBDA { A(decltype(i)::value, K) = c.template get<decltype(i)::value>(); });
    });
    detail::static_for<3>([&](auto k) FLANGE_INLINE_LAMBDA {
      constexpr int K = decltype(k)::value;
      if constexpr (detail::bit(AM, K)) {
        const auto c = rot_t(R, to_svec(Vec3<T>(A(K, 0), A(K, 1), A(K, 2))));
        detail::static_for<3>([&](auto i) FLANGE_INLINE_LAMBDA { B(K, decltype(i)::value) = c.template get<decltype(i)::value>(); });
      } else {
        detail::static_for<3>([&](auto i) FLANGE_INLINE_LAMBDA { B(K, decltype(i)::value) = T(0); });
      }
    });
    return B;
  }
}

/// Eᵀ·X·E for a symmetric X (the result is symmetric). About a coordinate
/// axis I, with (I, j, k) cyclic, only the entries that turn are computed,
/// from the upper triangle: 14 products instead of the 24 of turning every
/// column and row,
///   Y_II = X_II,  Y_Ij = c·X_Ij − s·X_Ik,  Y_Ik = s·X_Ij + c·X_Ik,
///   Y_jj = c²·X_jj − 2cs·X_jk + s²·X_kk,  Y_kk = s²·X_jj + 2cs·X_jk + c²·X_kk,
///   Y_jk = cs·(X_jj − X_kk) + (c² − s²)·X_jk.
///
/// Z (−1: none) is a row and column X is known to have zero: a rotation about
/// axis Z keeps them zero and computes only Y_jj, Y_kk, Y_jk (an articulated
/// inertia's Θ behind a revolute joint, articulated_body.hpp); a rotation
/// about another axis skips them as factors (the second factor R_x(α) of an
/// axis frame's E).
template <class T, int Z = -1, class E>
FLANGE_INLINE Mat3<T> rotated_back_sym(const E& R, const Mat3<T>& X) {
  if constexpr (std::is_same_v<std::remove_cvref_t<E>, Mat3<T>>) {
    return small::congruence_sym(R, X);
  } else if constexpr (is_rotation_product<E>) {
    return rotated_back_sym<T, keeps_zero<decltype(R.a)>(Z)>(R.b, rotated_back_sym<T, Z>(R.a, X));
  } else if constexpr (requires { E::axis; }) {
    constexpr int I = E::axis, j = E::j, k = E::k;
    const T cc = R.c * R.c, ss = R.s * R.s, cs = R.c * R.s;
    Mat3<T> Y;
    if constexpr (Z == j || Z == k) {
      // Row and column Z zero, turned out of place: with x the row's one
      // other entry and d the diagonal entry left in the plane (Z = k:
      // x = X_Ij, d = X_jj; Z = j: x = X_Ik, d = X_kk), 5 products:
      //   Z = k:  Y_Ij = c·x,  Y_Ik = s·x,  Y_jj = c²·d,  Y_kk = s²·d,  Y_jk = cs·d
      //   Z = j:  Y_Ij = −s·x, Y_Ik = c·x,  Y_jj = s²·d,  Y_kk = c²·d,  Y_jk = −cs·d
      constexpr bool kz = Z == k;
      const T x = kz ? X(I, j) : X(I, k), d = kz ? X(j, j) : X(k, k);
      Y(I, I) = X(I, I);
      Y(I, j) = Y(j, I) = kz ? R.c * x : -(R.s * x);
      Y(I, k) = Y(k, I) = kz ? R.s * x : R.c * x;
      Y(j, j) = (kz ? cc : ss) * d;
      Y(k, k) = (kz ? ss : cc) * d;
      Y(j, k) = Y(k, j) = kz ? cs * d : -(cs * d);
      return Y;
    }
    const T t = T(2) * cs * X(j, k);
    if constexpr (I == Z) {
      Y(I, I) = Y(I, j) = Y(j, I) = Y(I, k) = Y(k, I) = T(0);
    } else {
      Y(I, I) = X(I, I);
      Y(I, j) = Y(j, I) = R.c * X(I, j) - R.s * X(I, k);
      Y(I, k) = Y(k, I) = R.s * X(I, j) + R.c * X(I, k);
    }
    Y(j, j) = cc * X(j, j) - t + ss * X(k, k);
    Y(k, k) = ss * X(j, j) + t + cc * X(k, k);
    Y(j, k) = Y(k, j) = cs * (X(j, j) - X(k, k)) + (cc - ss) * X(j, k);
    return Y;
  } else {
    return rotated_back<T, Z>(R, X);
  }
}

/// The same for a general E applied to X's columns and then to the rows of
/// the result (54 products, no symmetry used). The products are the same as
/// rotated_back_sym's; GCC schedules the two differently, and which is faster
/// depends on the pass around them: this one inside the mass matrix's pass,
/// the other inside the articulated body (docs/performance.md, "Why the hot
/// path is written as it is").
template <class T, class E>
FLANGE_INLINE Mat3<T> rotated_back_sym_by_columns(const E& R, const Mat3<T>& X) {
  if constexpr (std::is_same_v<std::remove_cvref_t<E>, Mat3<T>>) {
    Mat3<T> A;
    for (int k = 0; k < 3; ++k) A.col(k) = rot_t(R, to_svec(Vec3<T>(X.col(k)))).dense();
    Mat3<T> B;
    for (int k = 0; k < 3; ++k) B.col(k) = rot_t(R, to_svec(Vec3<T>(A.row(k).transpose()))).dense();
    return B.transpose();
  } else {
    return rotated_back_sym<T>(R, X);
  }
}

}  // namespace flange
