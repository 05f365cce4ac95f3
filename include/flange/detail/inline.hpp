// FLANGE_INLINE: forces inlining of the small steps the recursive algorithms
// are made of (a link's forward step, a wrench carried up, a composite inertia
// shifted). The compiler's own heuristics decline to inline a step that is
// called once per link with the same types; a call then passes its typed
// operands through memory, which costs more than the step. GCC and clang
// both honour the attribute.
#pragma once

#define FLANGE_INLINE [[gnu::always_inline]] inline

/// The same for a lambda: [&](auto i) FLANGE_INLINE_LAMBDA { … }.
#define FLANGE_INLINE_LAMBDA __attribute__((always_inline))
