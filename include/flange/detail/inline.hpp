// FLANGE_INLINE: forces inlining of the small steps the recursive algorithms
// are made of (a link's forward step, a wrench carried up, a composite inertia
// shifted). The compiler's own heuristics decline to inline a step that is
// called once per link with the same types; a call then passes its typed
// operands through memory, which costs more than the step. GCC and clang
// both honour the attribute.
//
// Defining FLANGE_NO_FORCED_INLINE (the same in every translation unit of a
// program, before any flange header) leaves inlining to the compiler: the
// same numbers, from code that compiles faster and runs slower (GCC 12:
// tests/chain_test.cpp at -O1 98 → 73 s of compiler, examples/robot_arm.cpp
// at -O3 15.8 → 14.3 s). The tests build so (all but no_heap_test; the
// test inline.same_numbers holds the two builds to the same bits); the
// examples do not, nor do the benchmarks unless configured with
// -DFLANGE_BENCHMARK_TIMING=OFF (as the README's test command builds them).
#pragma once

#ifdef FLANGE_NO_FORCED_INLINE
#define FLANGE_INLINE inline
#define FLANGE_INLINE_LAMBDA
#else
#define FLANGE_INLINE [[gnu::always_inline]] inline

/// The same for a lambda: [&](auto i) FLANGE_INLINE_LAMBDA { … }.
#define FLANGE_INLINE_LAMBDA __attribute__((always_inline))
#endif
