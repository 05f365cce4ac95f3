# flange_precompile_headers(<target> [HEADERS <header>...] [INLINE_STEPS])
#
# Precompiles <flange/flange.hpp> (or the HEADERS given, e.g.
# <flange/equations_of_motion.hpp>) for <target>, through CMake's
# target_precompile_headers: the target's units then start from the parsed
# headers instead of parsing Eigen, Hana, Odeint and flange again each time.
# It also compiles flange's scene-independent code once for the target
# (FLANGE_COMMON, flange/detail/lazy.hpp: the parameter checks, a body's
# placement in its link, error messages): the target's units declare it
# extern (FLANGE_COMMON_EXTERN) and call it, and one added unit,
# flange_common.cpp, defines it. The header and that unit are built once
# per target (about twice and once the time of a small scene's unit without
# them) and again only when flange's headers or the target's flags change;
# each unit of the target then compiles in the time of its scene's
# instantiations alone: a pendulum's unit in about a sixth of its time
# without them (docs/performance.md, "Compile time"). The target's runs of
# simulate's default method share their steps too (FLANGE_SHARED_STEPS,
# below).
#
#   add_executable(my_sim my_sim.cpp)
#   target_link_libraries(my_sim PRIVATE flange::flange)
#   flange_precompile_headers(my_sim)
#
# Several targets with the same flags can share one precompiled header:
# target_precompile_headers(other REUSE_FROM my_sim), with
# flange_common_code(other) for the extern code (or, for many targets, one
# flange_common_library(common) and flange_common_code(t OBJECTS common))
# and FLANGE_SHARED_STEPS defined as for my_sim (on the library too).
set(_flange_common_source ${CMAKE_CURRENT_LIST_DIR}/flange_common.cpp)

# flange_common_code(<target> [OBJECTS <library>]): the target's units
# declare flange's scene-independent code extern, and flange_common.cpp,
# added to the target without a precompiled header, defines it. With
# OBJECTS, the target links that library's copy instead (one made by
# flange_common_library): targets with the same flags then compile it once
# between them.
function(flange_common_code target)
  cmake_parse_arguments(FC "" "OBJECTS" "" ${ARGN})
  target_compile_definitions(${target} PRIVATE FLANGE_COMMON_EXTERN)
  if(FC_OBJECTS)
    target_sources(${target} PRIVATE $<TARGET_OBJECTS:${FC_OBJECTS}>)
  else()
    target_sources(${target} PRIVATE ${_flange_common_source})
    set_source_files_properties(${_flange_common_source} TARGET_DIRECTORY ${target}
                                PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()

# flange_common_library(<name>): an OBJECT library of flange_common.cpp, for
# flange_common_code(<target> OBJECTS <name>).
function(flange_common_library name)
  add_library(${name} OBJECT ${_flange_common_source})
  target_link_libraries(${name} PRIVATE flange::flange)
endfunction()

function(flange_precompile_headers target)
  cmake_parse_arguments(FP "INLINE_STEPS" "" "HEADERS" ${ARGN})
  if(NOT FP_HEADERS)
    set(FP_HEADERS <flange/flange.hpp>)
  endif()
  target_precompile_headers(${target} PRIVATE ${FP_HEADERS})
  flange_common_code(${target})
  # simulate's default method steps a scene through a type-erased system,
  # its steps compiled once in flange_common.cpp for states of up to 16
  # numbers (flange/simulate/method.hpp): a small scene's unit about 0.5 s
  # faster, each derivative evaluation of a run an indirect call (the
  # paper's arm simulates 1.3-1.45 times slower, the crane 1.0-1.1 times).
  # INLINE_STEPS keeps the steps in each unit, the scene's derivative
  # inlined into them.
  if(NOT FP_INLINE_STEPS)
    target_compile_definitions(${target} PRIVATE FLANGE_SHARED_STEPS)
  endif()
  # GCC (up to 12) does not keep the "#pragma GCC diagnostic" state of the
  # precompiled headers: Eigen's silencing of -Wignored-attributes (an
  # attribute of its SIMD packet types, harmless) is lost, and every unit
  # that instantiates Eigen warns, though the same unit without the
  # precompiled header is clean.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-ignored-attributes)
  endif()
endfunction()
