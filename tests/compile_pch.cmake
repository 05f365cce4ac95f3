# The compile-only tests (compile_fail/check.cmake, snippets/compile.cmake)
# read <flange/equations_of_motion.hpp> from the precompiled copy that
# tests/CMakeLists.txt builds: PCH names a header that includes it, with its
# .gch beside it. A source gets it only when its first #include is that
# header or <flange/flange.hpp> (which includes it first), so it sees the
# same text in the same order (a compile-fail case: 8.4 → 2.7 s). Without a
# current .gch (a compiler other than GCC; ctest before a build, or after a
# flange header changed and before the next build: GCC would read the old
# copy) the source is compiled as it is.
function(flange_pch_args src out)
  set(${out} "" PARENT_SCOPE)
  if(NOT DEFINED PCH OR NOT EXISTS "${PCH}.gch" OR NOT EXISTS "${PCH}.d")
    return()
  endif()
  file(STRINGS ${src} includes REGEX "^#include ")
  list(LENGTH includes n)
  if(n EQUAL 0)
    return()
  endif()
  list(GET includes 0 first)
  if(NOT first MATCHES "^#include <flange/(flange|equations_of_motion)\\.hpp>")
    return()
  endif()
  # The flange headers the copy was made from (its depfile) must be older.
  file(READ "${PCH}.d" deps)
  string(REGEX MATCHALL "[^ \\\\\n]+/include/flange/[^ \\\\\n]+\\.hpp" headers "${deps}")
  foreach(h IN LISTS headers)
    if("${h}" IS_NEWER_THAN "${PCH}.gch")
      message(STATUS "${h} is newer than the precompiled copy: compiled without it")
      return()
    endif()
  endforeach()
  set(${out} -include ${PCH} PARENT_SCOPE)
endfunction()
