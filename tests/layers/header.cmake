# Compiles one public header on its own (nothing included before it).
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only ${INCLUDES} -x c++ -include ${HEADER} /dev/null
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${HEADER} does not compile on its own:\n${out}${err}")
endif()
