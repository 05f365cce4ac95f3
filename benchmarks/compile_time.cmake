# Times the compilation of each translation unit given in SOURCES, and of
# each in PCH_SOURCES as flange_precompile_headers builds it: against a
# precompiled flange.hpp (built first, in PCH_DIR, and timed itself), with
# flange's scene-independent code extern (FLANGE_COMMON_EXTERN; its one
# unit, COMMON_SOURCE, timed once too). Compiler CPU time (user + system,
# from bash's `time -p`), the median of three compiles, at the flags of a
# Release build.
# Writes "unit,seconds" rows to OUTPUT ("+pch" after a unit compiled with the
# precompiled header).
string(REPLACE "|" ";" sources "${SOURCES}")
string(REPLACE "|" ";" pch_sources "${PCH_SOURCES}")
string(REPLACE "|" ";" flags "${FLAGS}")
file(WRITE ${OUTPUT} "unit,seconds\n")

# The median CPU time of three runs of the command in ARGN, in `seconds`.
function(cpu_time_of name)
  set(runs "")
  foreach(i 1 2 3)
    list(JOIN ARGN " " cmd)
    execute_process(COMMAND bash -c "TIMEFORMAT='%2U %2S'; { time ${cmd} >/dev/null 2>&1 ; } 2>&1"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "compile_time: ${name} did not compile")
    endif()
    string(STRIP "${out}" out)
    string(REGEX MATCHALL "[0-9.]+" parts "${out}")
    list(GET parts -2 user)
    list(GET parts -1 sys)
    # hundredths of a second, summed
    string(REPLACE "." "" u "${user}")
    string(REPLACE "." "" s "${sys}")
    math(EXPR t "${u} + ${s}")
    list(APPEND runs ${t})
  endforeach()
  list(SORT runs COMPARE NATURAL)
  list(GET runs 1 med)
  math(EXPR whole "${med} / 100")
  math(EXPR frac "${med} % 100")
  if(frac LESS 10)
    set(frac "0${frac}")
  endif()
  file(APPEND ${OUTPUT} "${name},${whole}.${frac}\n")
endfunction()

foreach(src IN LISTS sources)
  get_filename_component(name ${src} NAME_WE)
  cpu_time_of(${name} ${CXX} ${flags} -c ${src} -o ${CMAKE_CURRENT_BINARY_DIR}/${name}.timing.o)
endforeach()
if(pch_sources)
  # The header beside its precompiled form: GCC takes the .gch, and reads
  # the header's path when the unit includes it again.
  file(MAKE_DIRECTORY ${PCH_DIR}/flange)
  file(COPY ${PCH_HEADER} DESTINATION ${PCH_DIR}/flange)
  cpu_time_of("flange.hpp.gch (once)" ${CXX} ${flags} -DFLANGE_COMMON_EXTERN -DFLANGE_SHARED_STEPS -x c++-header ${PCH_HEADER}
              -o ${PCH_DIR}/flange/flange.hpp.gch)
  cpu_time_of("flange_common.cpp (once)" ${CXX} ${flags} -DFLANGE_COMMON_EXTERN -DFLANGE_SHARED_STEPS -c ${COMMON_SOURCE}
              -o ${CMAKE_CURRENT_BINARY_DIR}/flange_common.timing.o)
  foreach(src IN LISTS pch_sources)
    get_filename_component(name ${src} NAME_WE)
    # -Wno-ignored-attributes as flange_precompile_headers gives it (GCC loses
    # Eigen's silencing of it in a precompiled header).
    cpu_time_of("${name}+pch" ${CXX} -I${PCH_DIR} ${flags} -DFLANGE_COMMON_EXTERN -DFLANGE_SHARED_STEPS -Wno-ignored-attributes
                -include flange/flange.hpp -Winvalid-pch -c ${src}
                -o ${CMAKE_CURRENT_BINARY_DIR}/${name}.pch.timing.o)
  endforeach()
endif()
