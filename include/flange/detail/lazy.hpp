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
//
// FLANGE_COMMON(declaration), after such a function (or a function template
// used at T = double), names one specialization that does not depend on the
// scene: a parameter check, a body's placement in its link, an error
// message. Such code is the same in every unit; a unit that calls it still
// instantiates and optimises it (about a third of a small scene's compile).
// Where FLANGE_COMMON_EXTERN is defined, each is an explicit instantiation
// declaration (`extern template`): the units call it and compile none of it,
// and one unit of the target, cmake/flange_common.cpp, defines
// FLANGE_COMMON_DEFINE and compiles them all once.
// flange_precompile_headers (cmake/flange_pch.cmake) does both for a
// target. Otherwise it is nothing, and flange stays header-only. The
// functions named are not `inline`: an explicit instantiation declaration
// does not keep an inline function from being instantiated.
#pragma once

#define FLANGE_LAZY template <int = 0>

#if defined(FLANGE_COMMON_DEFINE)
#define FLANGE_COMMON(...) template __VA_ARGS__;
#elif defined(FLANGE_COMMON_EXTERN)
#define FLANGE_COMMON(...) extern template __VA_ARGS__;
#else
#define FLANGE_COMMON(...)
#endif
