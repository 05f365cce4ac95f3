// flange's scene-independent functions (FLANGE_COMMON, flange/detail/lazy.hpp:
// the parameter checks, a body's placement in its link, error messages),
// compiled once for a target whose other units declare them extern
// (FLANGE_COMMON_EXTERN): flange_precompile_headers (flange_pch.cmake) adds
// this unit to the target, without the precompiled header.
#define FLANGE_COMMON_DEFINE
#include <flange/flange.hpp>
