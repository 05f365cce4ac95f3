# flange_precompile_headers(<target> [HEADERS <header>...])
#
# Precompiles <flange/flange.hpp> (or the HEADERS given, e.g.
# <flange/equations_of_motion.hpp>) for <target>, through CMake's
# target_precompile_headers: the target's units then start from the parsed
# headers instead of parsing Eigen, Hana, Odeint and flange again each time.
# The header is built once per target (about 14 s of compiler time) and
# again only when flange's headers or the target's flags change; each unit
# of the target saves about 4 s on every later compile, so an edit of a
# scene recompiles in the time of its instantiations alone
# (docs/performance.md, "Compile time").
#
#   add_executable(my_sim my_sim.cpp)
#   target_link_libraries(my_sim PRIVATE flange::flange)
#   flange_precompile_headers(my_sim)
#
# Several targets with the same flags can share one precompiled header:
# target_precompile_headers(other REUSE_FROM my_sim).
function(flange_precompile_headers target)
  cmake_parse_arguments(FP "" "" "HEADERS" ${ARGN})
  if(NOT FP_HEADERS)
    set(FP_HEADERS <flange/flange.hpp>)
  endif()
  target_precompile_headers(${target} PRIVATE ${FP_HEADERS})
  # GCC (up to 12) does not keep the "#pragma GCC diagnostic" state of the
  # precompiled headers: Eigen's silencing of -Wignored-attributes (an
  # attribute of its SIMD packet types, harmless) is lost, and every unit
  # that instantiates Eigen warns, though the same unit without the
  # precompiled header is clean.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-ignored-attributes)
  endif()
endfunction()
