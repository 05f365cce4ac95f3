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
