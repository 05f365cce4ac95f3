# The compile-only tests (compile_fail/check.cmake, snippets/compile.cmake)
# read <flange/equations_of_motion.hpp> from the precompiled copy that
# tests/CMakeLists.txt builds: PCH names a header that includes it, with its
# .gch beside it. A source gets it only when its first #include is that
# header or <flange/flange.hpp> (which includes it first), so it sees the
# same text in the same order, parsed in 0.3 s instead of 6. Without the .gch
# (a compiler other than GCC, or ctest before a build) the source is compiled
# as it is.
function(flange_pch_args src out)
  set(args "")
  if(DEFINED PCH AND EXISTS "${PCH}.gch")
    file(STRINGS ${src} includes REGEX "^#include ")
    list(LENGTH includes n)
    if(n GREATER 0)
      list(GET includes 0 first)
      if(first MATCHES "^#include <flange/(flange|equations_of_motion)\\.hpp>")
        set(args -include ${PCH})
      endif()
    endif()
  endif()
  set(${out} ${args} PARENT_SCOPE)
endfunction()
