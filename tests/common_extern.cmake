# That FLANGE_COMMON_EXTERN reaches a unit (detail/lazy.hpp): in its object
# file flange's scene-independent code is called, not compiled (nm: "U"),
# and the one unit that defines it (flange_common.cpp) holds it ("W").
#   cmake -DNM=<nm> -DUNIT=<object> -DCOMMON=<object> [-DSYMBOL=<name>] -P common_extern.cmake
# SYMBOL is the start of the demangled functions looked for (every one found
# in the unit must be called only), by default a Body's parameter check.
if(NOT SYMBOL)
  set(SYMBOL "void flange::detail::check_body<0>(")
endif()
string(REGEX REPLACE "([().*+?])" "\\\\\\1" symbol_re "${SYMBOL}")
function(symbol_kinds object out)
  execute_process(COMMAND ${NM} -C ${object} OUTPUT_VARIABLE listing RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} -C ${object} failed")
  endif()
  string(REGEX MATCHALL " [A-Za-z] ${symbol_re}" lines "${listing}")
  set(kinds "")
  foreach(line IN LISTS lines)
    string(SUBSTRING "${line}" 1 1 kind)
    list(APPEND kinds ${kind})
  endforeach()
  set(${out} "${kinds}" PARENT_SCOPE)
endfunction()
symbol_kinds(${UNIT} unit_kinds)
symbol_kinds(${COMMON} common_kinds)
if(NOT unit_kinds MATCHES "^U(;U)*$")
  message(FATAL_ERROR "${UNIT}: ${SYMBOL}…) is \"${unit_kinds}\" there, not only called (U): FLANGE_COMMON_EXTERN did not reach the unit")
endif()
if(NOT common_kinds MATCHES "^[WT](;[WT])*$")
  message(FATAL_ERROR "${COMMON}: ${SYMBOL}…) is \"${common_kinds}\" there, not defined (W or T)")
endif()
list(LENGTH unit_kinds n)
message(STATUS "${SYMBOL}…) (${n} in the unit): called in the unit, defined in flange_common.cpp")
