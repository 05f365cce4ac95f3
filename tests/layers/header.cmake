# Compiles one public header on its own (nothing included before it).
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${INCLUDES} -x c++ -include ${HEADER} /dev/null
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${HEADER} does not compile on its own:\n${out}${err}")
endif()
# FORBID: a path that must not be among the header's includes, direct or not
# (equations_of_motion.hpp must not pull in Boost.Odeint: that is its point).
if(DEFINED FORBID)
  execute_process(COMMAND ${CXX} -std=c++20 -M ${INCLUDES} -x c++ -include ${HEADER} /dev/null
                  RESULT_VARIABLE rc OUTPUT_VARIABLE deps ERROR_VARIABLE err)
  string(FIND "${deps}" "${FORBID}" pos)
  if(NOT rc EQUAL 0 OR NOT pos EQUAL -1)
    message(FATAL_ERROR "${HEADER} includes ${FORBID} (or its dependencies could not be listed):\n${err}")
  endif()
endif()
