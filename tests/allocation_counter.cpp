// The allocation counter of the no-heap tests (no_heap_test.cpp,
// large_scenes_test.cpp): every way to the heap is counted.
//   * malloc, calloc, realloc, aligned_alloc and posix_memalign, wrapped at
//     link time (-Wl,--wrap=…, see CMakeLists.txt): Eigen allocates through
//     these, and EIGEN_RUNTIME_NO_MALLOC, an assertion, is gone in Release;
//   * every replaceable operator new and delete (plain, array, nothrow,
//     aligned), replaced to go through malloc and free: one allocator for all,
//     so AddressSanitizer sees matching pairs.
// A program links this file once; tests read the count through
// allocation_counter.hpp.
#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>

#include "allocation_counter.hpp"

namespace {
std::atomic<long> allocations{0};
}

long flange::test::allocations_so_far() { return allocations; }

extern "C" {
void* __real_malloc(std::size_t);
void* __real_calloc(std::size_t, std::size_t);
void* __real_realloc(void*, std::size_t);
void* __real_aligned_alloc(std::size_t, std::size_t);
int __real_posix_memalign(void**, std::size_t, std::size_t);
void* __wrap_malloc(std::size_t n) {
  ++allocations;
  return __real_malloc(n);
}
void* __wrap_calloc(std::size_t k, std::size_t n) {
  ++allocations;
  return __real_calloc(k, n);
}
void* __wrap_realloc(void* p, std::size_t n) {
  ++allocations;
  return __real_realloc(p, n);
}
void* __wrap_aligned_alloc(std::size_t a, std::size_t n) {
  ++allocations;
  return __real_aligned_alloc(a, n);
}
int __wrap_posix_memalign(void** p, std::size_t a, std::size_t n) {
  ++allocations;
  return __real_posix_memalign(p, a, n);
}
}

namespace {
void* allocate(std::size_t n) { return std::malloc(n ? n : 1); }
void* allocate(std::size_t n, std::align_val_t a) {
  const std::size_t al = std::max(static_cast<std::size_t>(a), sizeof(void*));
  void* p = nullptr;
  return posix_memalign(&p, al, n ? n : 1) == 0 ? p : nullptr;
}
template <class... A>
void* allocate_or_throw(std::size_t n, A... a) {
  if (void* p = allocate(n, a...)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return allocate_or_throw(n); }
void* operator new[](std::size_t n) { return allocate_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return allocate_or_throw(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocate_or_throw(n, a); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate(n, a); }
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }

