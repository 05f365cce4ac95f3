# tools/header_chains.py and header.cmake on a fixture (chain_fixture/): a
# header that does not compile on its own (lacks.hpp), included by one that
# does (top.hpp), is found by its chain's single compilation; and a chain
# whose headers no longer include each other is refused, not half-checked.
set(root ${CMAKE_CURRENT_LIST_DIR}/chain_fixture)
execute_process(COMMAND ${PYTHON} ${CHAINS} --root ${root} flange/top.hpp flange/lacks.hpp flange/base.hpp
                OUTPUT_VARIABLE chains RESULT_VARIABLE rc COMMAND_ERROR_IS_FATAL ANY)
string(STRIP "${chains}" chains)
if(NOT chains STREQUAL "flange/base.hpp;flange/lacks.hpp;flange/top.hpp")
  message(FATAL_ERROR "expected one chain base, lacks, top; got:\n${chains}")
endif()
string(REPLACE ";" "," chain "${chains}")
execute_process(COMMAND ${CMAKE_COMMAND} -DCXX=${CXX} -DINCLUDES=-I${root} -DROOT=${root} -DHEADERS=${chain} -DPYTHON=${PYTHON}
                        -DCHAINS=${CHAINS} -P ${CMAKE_CURRENT_LIST_DIR}/header.cmake
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "lacks\\.hpp:[0-9]+:[0-9]+:[ \n]*error:")
  message(FATAL_ERROR "the chain's compilation did not refuse lacks.hpp:\n${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -DCXX=${CXX} -DINCLUDES=-I${root} -DROOT=${root} -DHEADERS=flange/top.hpp -P ${CMAKE_CURRENT_LIST_DIR}/header.cmake
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "top.hpp alone should compile (the fixture is wrong):\n${out}${err}")
endif()
execute_process(COMMAND ${PYTHON} ${CHAINS} --root ${root} --check flange/top.hpp,flange/base.hpp
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(rc EQUAL 0 OR NOT out MATCHES "re-run cmake")
  message(FATAL_ERROR "a chain out of order was not refused: ${out}")
endif()
message(STATUS "the chains find a header that does not compile alone, and refuse a stale chain")
