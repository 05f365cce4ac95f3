# flange_urdf_scene(<target> <robot.urdf> [NAMESPACE <ns>] [FLOATING_BASE]
#                   [STOP_STIFFNESS <k>] [STOP_DISSIPATION <d>] [NO_LIMITS])
#
# Runs flange-urdf on the URDF file at build time (again whenever the file
# changes) and makes the generated header, <ns>.hpp, includable by <target>:
#
#   flange_urdf_scene(my_app robots/arm.urdf NAMESPACE arm)
#   // my_app.cpp:  #include "arm.hpp"   auto robot = arm::make_scene();
#
# <ns> defaults to the file's name without its extension. FLOATING_BASE lets
# the root link move freely where the URDF has no floating joint (flange-urdf
# --floating-base). Joint limits become compliant stops of stiffness <k>
# (default 1e4) and dissipation <d> (default 1); NO_LIMITS leaves them out
# (flange-urdf --stop-stiffness, --stop-dissipation, --no-limits).
function(flange_urdf_scene target urdf)
  cmake_parse_arguments(FU "FLOATING_BASE;NO_LIMITS" "NAMESPACE;STOP_STIFFNESS;STOP_DISSIPATION" "" ${ARGN})
  set(extra "")
  if(FU_FLOATING_BASE)
    list(APPEND extra --floating-base)
  endif()
  if(FU_NO_LIMITS)
    list(APPEND extra --no-limits)
  endif()
  if(DEFINED FU_STOP_STIFFNESS)
    list(APPEND extra --stop-stiffness ${FU_STOP_STIFFNESS})
  endif()
  if(DEFINED FU_STOP_DISSIPATION)
    list(APPEND extra --stop-dissipation ${FU_STOP_DISSIPATION})
  endif()
  get_filename_component(urdf_path "${urdf}" ABSOLUTE)
  if(NOT FU_NAMESPACE)
    get_filename_component(FU_NAMESPACE "${urdf}" NAME_WE)
  endif()
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/flange_urdf/${target}")
  set(header "${dir}/${FU_NAMESPACE}.hpp")
  add_custom_command(
    OUTPUT "${header}"
    COMMAND ${CMAKE_COMMAND} -E make_directory "${dir}"
    COMMAND $<TARGET_FILE:flange::urdf> "${urdf_path}" --namespace ${FU_NAMESPACE} ${extra} -o "${header}"
    DEPENDS "${urdf_path}" $<TARGET_FILE:flange::urdf>
    COMMENT "flange-urdf ${urdf} -> ${FU_NAMESPACE}.hpp"
    VERBATIM)
  target_sources(${target} PRIVATE "${header}")
  target_include_directories(${target} PRIVATE "${dir}")
endfunction()
