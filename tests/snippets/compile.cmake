# Compiles one program of the documents' snippets (tools/doc_snippets.py),
# syntax and template instantiation, no code generation: the test that the
# README and docs show code that compiles with the includes they show.
# PCH: the precompiled <flange/equations_of_motion.hpp> (compile_pch.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/../compile_pch.cmake)
flange_pch_args(${SOURCE} pch)
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only -Wall -Wextra -Wpedantic -Wno-unused -Wno-unused-result
                        -Wno-unused-parameter ${INCLUDES} ${pch} ${SOURCE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "a snippet does not compile (the errors name the document's lines):\n${out}${err}")
endif()
if(NOT "${err}" STREQUAL "")
  message(FATAL_ERROR "a snippet compiles with warnings:\n${err}")
endif()
