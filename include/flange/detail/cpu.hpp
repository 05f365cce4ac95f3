// What the processor runs, asked once at start-up, for the few kernels that
// pick their instructions at run time (math/sincos.hpp's cosines,
// math/tree_solve.hpp's triangular solves): the library is built for the
// SSE2 every x86-64 has unless its users ask for more (-march), so wider
// instructions are chosen here, where the processor has them.
//
// FLANGE_X86_DISPATCH is defined where that choice is made (x86-64 with GCC
// or Clang); elsewhere every kernel takes its portable code.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FLANGE_X86_DISPATCH 1
#endif

namespace flange::detail {
#ifdef FLANGE_X86_DISPATCH
/// Whether the processor (and the operating system) run AVX2.
inline const bool cpu_has_avx2 = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
}();
/// Whether they run AVX2 and fused multiply-adds (FMA3).
inline const bool cpu_has_avx2_fma = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0;
}();
#else
inline constexpr bool cpu_has_avx2 = false;
inline constexpr bool cpu_has_avx2_fma = false;
#endif
}  // namespace flange::detail
