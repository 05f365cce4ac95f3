# Runs one half of a compile-fail pair.
#   MODE=ok: SRC must compile (the ok halves, all in one generated source:
#            tests/CMakeLists.txt).
#   MODE=ko: SRC with -DFLANGE_KO must fail, and the compiler output must
#            contain every string in EXPECT (the diagnostic and its culprit),
#            with exactly one error line and at most 25 lines in all.
#   PCH: the precompiled <flange/equations_of_motion.hpp> (compile_pch.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/../compile_pch.cmake)
flange_pch_args(${SRC} pch)
set(args -std=c++20 -fsyntax-only ${INCLUDES} ${pch} ${SRC})
if(MODE STREQUAL "ko")
  list(APPEND args -DFLANGE_KO)
endif()
execute_process(COMMAND ${CXX} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(all "${out}${err}")
if(MODE STREQUAL "ok")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the ok half did not compile:\n${all}")
  endif()
  return()
endif()
if(rc EQUAL 0)
  message(FATAL_ERROR "the ko half compiled, but it must be refused")
endif()
foreach(e IN LISTS EXPECT)
  string(FIND "${all}" "${e}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "the ko half failed, but its output lacks\n  ${e}\noutput:\n${all}")
  endif()
endforeach()
# One diagnostic, not a cascade of unrelated errors, and short enough to
# read: one error line, and at most 25 lines of compiler output in all.
string(REGEX MATCHALL "error:" errors "${all}")
list(LENGTH errors n)
string(REGEX MATCHALL "\n" newlines "${all}")
list(LENGTH newlines lines)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "the ko half gave ${n} errors, not one:\n${all}")
endif()
if(lines GREATER 25)
  message(FATAL_ERROR "the ko half's output is ${lines} lines, more than 25:\n${all}")
endif()
message(STATUS "refused as expected (1 error, ${lines} lines)")
