// FLANGE_LAZY, written before a function that is not otherwise a template:
// `template <int = 0>`, so that the templates its body uses (Eigen's
// expressions, the standard library's formatting) are instantiated only in
// the translation units that call it. GCC instantiates what a plain inline
// function uses in every unit that includes its header, called or not, at
// the end of the unit and again after a precompiled header: flange.hpp's
// plain functions cost every unit 91 MB of g++'s memory and about 1.3 s that
// way, 26 MB and 0.3 s written lazily (docs/performance.md, "Compile time").
// A call is written as before; a function whose body uses only built-in
// types needs none of this.
#pragma once

#define FLANGE_LAZY template <int = 0>
