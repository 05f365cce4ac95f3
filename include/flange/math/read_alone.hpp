// Reading what another step has just written, one scalar at a time.
//
// A step of a long chain often reads what the step before it wrote moments
// ago: in the articulated body (dynamics/articulated_body.hpp) a link's
// articulated inertia and bias force, which its child's step has just added
// to entry by entry. GCC's vectoriser reads two neighbouring entries as one
// 16-byte load. A load that spans two 8-byte stores still in flight cannot
// take its value from the store buffer: it waits until both stores reach the
// cache (store forwarding fails), and that wait is on the chain that runs
// link after link. read_alone(x) is a copy of x whose scalars are each read by
// themselves, through an empty asm the vectoriser does not see through, so
// that each load is forwarded from its own store. It adds no instruction.
#pragma once
#include "flange/detail/inline.hpp"
#include "flange/math/sparse.hpp"
#include "flange/math/types.hpp"
#include <type_traits>

namespace flange {

template <class T>
FLANGE_INLINE T read_alone(const T& x) {
  T v = x;
#if defined(__GNUC__) && defined(__SSE2__)
  if constexpr (std::is_same_v<T, double>) asm("" : "+x"(v));
#endif
  return v;
}
template <class T, int R, int C>
FLANGE_INLINE Eigen::Matrix<T, R, C> read_alone(const Eigen::Matrix<T, R, C>& m) {
  Eigen::Matrix<T, R, C> r;
  for (int i = 0; i < R * C; ++i) r.data()[i] = read_alone(m.data()[i]);
  return r;
}
template <class T, int M>
FLANGE_INLINE svec<T, M> read_alone(const svec<T, M>& v) {
  if constexpr (M == 0) {
    return v;
  } else {
    svec<T, M> r;
    for (int i = 0; i < detail::popcount3(M); ++i) r.c_[i] = read_alone(v.c_[i]);
    return r;
  }
}

}  // namespace flange
