# flange_simbody_program(<target> <source>): a program on Simbody (Debian's
# libsimbody-dev), the peer that benchmarks/peers/simbody_peer.cpp and
# tests/simbody/stops_reference.cpp run. Simbody 3.7's headers do not compile
# as C++20, and Debian's library is built without NDEBUG, which changes its
# class layout: a translation unit with -DNDEBUG (the Release default)
# crashes in realizeTopology(). So such a program is C++17, includes no
# flange header, and undefines NDEBUG. Sets FLANGE_SIMBODY_FOUND in the
# caller's scope; without Simbody it builds nothing.
macro(flange_simbody_program target source)
  find_package(Simbody QUIET)
  set(FLANGE_SIMBODY_FOUND ${Simbody_FOUND})
  if(Simbody_FOUND)
    add_executable(${target} ${source})
    target_include_directories(${target} SYSTEM PRIVATE ${Simbody_INCLUDE_DIR})
    target_link_libraries(${target} PRIVATE ${Simbody_LIBRARIES} flange_warnings)
    target_compile_options(${target} PRIVATE -UNDEBUG)
    set_target_properties(${target} PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON CXX_EXTENSIONS OFF)
  endif()
endmacro()

# flange_simbody_reference(<test> <program> <source> <define> [<more tests>…]):
# a Simbody program that writes a reference trajectory for the test target
# <test> (and any further test targets listed after <define>):
# built, run at build time into <program>.txt, and the file's path given to
# the test as the macro <define>. Without Simbody the test builds without it.
function(flange_simbody_reference test program source define)
  flange_simbody_program(${program} ${source})
  if(FLANGE_SIMBODY_FOUND)
    set(out ${CMAKE_CURRENT_BINARY_DIR}/${program}.txt)
    add_custom_command(OUTPUT ${out} COMMAND ${program} ${out} DEPENDS ${program} COMMENT "Simbody: ${program}")
    add_custom_target(${program}_reference DEPENDS ${out})
    foreach(t ${test} ${ARGN})
      add_dependencies(${t} ${program}_reference)
      target_compile_definitions(${t} PRIVATE ${define}="${out}")
    endforeach()
  else()
    message(STATUS "flange: Simbody not found (tools/install-deps.sh --peers): ${test} runs without its Simbody cross-check")
  endif()
endfunction()
