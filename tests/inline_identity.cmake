# inline.same_numbers: the two builds of inline_identity.cpp (forced inline,
# and FLANGE_NO_FORCED_INLINE with FLANGE_SHARED_STEPS) print the same
# numbers to the last bit.
#   cmake -DFORCED=<program> -DPLAIN=<program> -P inline_identity.cmake
foreach(p FORCED PLAIN)
  execute_process(COMMAND ${${p}} RESULT_VARIABLE rc OUTPUT_VARIABLE out_${p} ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${${p}} failed (${rc}): ${err}")
  endif()
endforeach()
string(LENGTH "${out_FORCED}" n)
if(n LESS 1000)
  message(FATAL_ERROR "inline_identity printed too little to compare:\n${out_FORCED}")
endif()
if(NOT out_FORCED STREQUAL out_PLAIN)
  message(FATAL_ERROR "users' build and the tests' (FLANGE_NO_FORCED_INLINE, FLANGE_SHARED_STEPS) give different numbers:\n"
                      "forced:\n${out_FORCED}\nnot forced:\n${out_PLAIN}")
endif()
message(STATUS "the same numbers to the last bit in users' build and the tests' (${n} characters)")
