# Compiles public headers on their own: HEADERS, comma-separated, is a chain
# of tools/header_chains.py (each header includes the one before it), compiled
# as one unit with nothing before the first, which checks each of them as if
# alone. One header is a chain of one.
string(REPLACE "," ";" headers "${HEADERS}")
if(DEFINED PYTHON)
  list(LENGTH headers n)
  if(n GREATER 1)
    execute_process(COMMAND ${PYTHON} ${CHAINS} --root ${ROOT} --check ${HEADERS}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${out}${err}")
    endif()
  endif()
endif()
set(args "")
foreach(h IN LISTS headers)
  list(APPEND args -include ${ROOT}/${h})
endforeach()
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${INCLUDES} -x c++ ${args} /dev/null
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "a header does not compile on its own (the first error names it):\n${out}${err}")
endif()
message(STATUS "each compiles on its own: ${HEADERS}")
# FORBID: a path that must not be among the includes of a header checked
# alone, direct or not (equations_of_motion.hpp must not pull in
# Boost.Odeint: that is its point).
if(DEFINED FORBID)
  execute_process(COMMAND ${CXX} -std=c++20 -M ${INCLUDES} -x c++ ${args} /dev/null
                  RESULT_VARIABLE rc OUTPUT_VARIABLE deps ERROR_VARIABLE err)
  string(FIND "${deps}" "${FORBID}" pos)
  if(NOT rc EQUAL 0 OR NOT pos EQUAL -1)
    message(FATAL_ERROR "${HEADERS} includes ${FORBID} (or its dependencies could not be listed):\n${err}")
  endif()
endif()
