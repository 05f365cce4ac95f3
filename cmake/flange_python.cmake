# A compiled scene as a Python module (pybind11; docs/python.md).
#
#   flange_add_python_module(NAME <module> SCENE <header> FACTORY <function>
#                            [PARAMETERS <type>] [OUTPUT_DIRECTORY <dir>] [TIMING])
#
# The CMake target is <module>_python (the module file is <module>.*.so).
# builds <module> from the scene FACTORY makes: FACTORY() for a scene without
# run-time parameters, FACTORY(const PARAMETERS&) for one with them
# (PARAMETERS: a struct adapted to Boost.Hana, include/flange/python/parameters.hpp).
# SCENE is the header declaring the factory. The module and the `flange`
# package it imports go to OUTPUT_DIRECTORY (default:
# ${CMAKE_CURRENT_BINARY_DIR}/python), with a launcher, <dir>/python3: the
# interpreter the module is built for (flange_find_python's), with <dir> on
# its PYTHONPATH, so that
#
#   <dir>/python3 -c "import <module>"
#
# works whatever `python3` on PATH is (a pyenv or virtualenv interpreter
# without numpy, or of another Python version, cannot import the module). TIMING adds _time_derivative and _time_simulate, the C++ loops the
# Python benchmark compares with.
#
#   flange_urdf_python_module(NAME <module> URDF <file> [FLOATING_BASE] [OUTPUT_DIRECTORY <dir>]
#                             [STOP_STIFFNESS <k>] [STOP_DISSIPATION <d>] [NO_LIMITS])
#
# runs flange-urdf on the file and builds the module of its scene
# (<module>::make_scene(), undriven).
#
# Needs Debian's pybind11-dev and python3-dev (tools/install-deps.sh --python).
# oneTBB, where found, runs ensembles on threads.
#
#   flange_find_python()
#
# finds Python 3 (interpreter and headers) as find_package(Python3) does, but
# when Python3_EXECUTABLE is not given it takes the first interpreter that can
# import numpy: `python3` on PATH, else Debian's /usr/bin/python3. A pyenv or
# virtualenv interpreter first on PATH often lacks numpy, which the modules
# import; Debian's python3-numpy is installed for /usr/bin/python3.

# The `flange` package: installed, flangeConfig.cmake says where; in the
# source tree, python/flange.
if(FLANGE_PYTHON_PACKAGE_DIR)
  set(_FLANGE_PYTHON_PACKAGE_DIR "${FLANGE_PYTHON_PACKAGE_DIR}")
else()
  set(_FLANGE_PYTHON_PACKAGE_DIR "${CMAKE_CURRENT_LIST_DIR}/../python/flange")
endif()

macro(flange_find_python)
  if(NOT Python3_EXECUTABLE)
    find_program(_flange_python_on_path NAMES python3 NO_CACHE)
    foreach(_flange_python IN ITEMS ${_flange_python_on_path} /usr/bin/python3)
      if(EXISTS "${_flange_python}")
        execute_process(COMMAND "${_flange_python}" -c "import numpy"
                        RESULT_VARIABLE _flange_no_numpy OUTPUT_QUIET ERROR_QUIET)
        if(_flange_no_numpy EQUAL 0)
          set(Python3_EXECUTABLE "${_flange_python}" CACHE FILEPATH
              "the Python 3 interpreter the flange modules are built for (one with numpy)")
          break()
        endif()
      endif()
    endforeach()
    if(NOT Python3_EXECUTABLE)
      message(STATUS "flange: no Python 3 interpreter here imports numpy (apt-get install python3-numpy); "
                     "the modules build, but importing them needs numpy")
    endif()
  endif()
  find_package(Python3 QUIET COMPONENTS Interpreter Development.Module)
endmacro()

# <dir>/python3: the modules' interpreter with <dir> first on PYTHONPATH.
function(_flange_python_launcher dir)
  set(python "${Python3_EXECUTABLE}")
  if(NOT python)
    set(python "${PYTHON_EXECUTABLE}")
  endif()
  if(NOT python)
    set(python python3)
  endif()
  file(MAKE_DIRECTORY "${dir}")
  file(WRITE "${dir}/python3.in"
"#!/bin/sh
# The Python the flange modules in this directory are built for, with this
# directory on its path (written by flange_add_python_module).
export PYTHONPATH=\"${dir}\${PYTHONPATH:+:\$PYTHONPATH}\"
exec \"${python}\" \"\$@\"
")
  file(COPY_FILE "${dir}/python3.in" "${dir}/python3" ONLY_IF_DIFFERENT)
  file(REMOVE "${dir}/python3.in")
  file(CHMOD "${dir}/python3" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                          WORLD_READ WORLD_EXECUTE)
endfunction()

function(flange_add_python_module)
  cmake_parse_arguments(FP "TIMING" "NAME;SCENE;FACTORY;PARAMETERS;OUTPUT_DIRECTORY" "" ${ARGN})
  set(target ${FP_NAME}_python)
  foreach(required NAME SCENE FACTORY)
    if(NOT FP_${required})
      message(FATAL_ERROR "flange_add_python_module: ${required} is missing")
    endif()
  endforeach()
  if(NOT TARGET pybind11::module)
    flange_find_python()
    if(NOT Python3_FOUND)
      message(FATAL_ERROR "flange_add_python_module: Python 3's interpreter and headers not found "
                          "(apt-get install python3-dev, or tools/install-deps.sh --python)")
    endif()
    find_package(pybind11 CONFIG REQUIRED)
  endif()
  if(NOT FP_OUTPUT_DIRECTORY)
    set(FP_OUTPUT_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/python")
  endif()
  get_filename_component(scene "${FP_SCENE}" ABSOLUTE)
  if(FP_PARAMETERS)
    set(params "${FP_PARAMETERS}")
    set(factory "[](const ${FP_PARAMETERS}& p) { return ${FP_FACTORY}(p); }")
  else()
    set(params "flange::python::no_parameters")
    set(factory "[](const flange::python::no_parameters&) { return ${FP_FACTORY}(); }")
  endif()
  set(timing_include "")
  set(timing_bind "")
  if(FP_TIMING)
    set(timing_include "#include <flange/python/timing.hpp>\n")
    set(timing_bind "  flange::python::bind_timing<${params}>(m, factory);\n")
  endif()
  set(src "${CMAKE_CURRENT_BINARY_DIR}/flange_python/${FP_NAME}_module.cpp")
  file(GENERATE OUTPUT "${src}" CONTENT
"// Generated by flange_add_python_module (cmake/flange_python.cmake).
#include \"${scene}\"
#include <flange/python/module.hpp>
${timing_include}
PYBIND11_MODULE(${FP_NAME}, m) {
  m.doc() = \"flange scene ${FP_FACTORY} from ${FP_SCENE}\";
  const auto factory = ${factory};
  flange::python::bind<${params}>(m, factory);
${timing_bind}}
")
  # NO_EXTRAS: no link-time optimisation (it would double the build time)
  pybind11_add_module(${target} MODULE NO_EXTRAS "${src}")
  target_link_libraries(${target} PRIVATE flange::flange)
  if(Python3_EXECUTABLE)
    target_compile_definitions(${target} PRIVATE "FLANGE_PYTHON_BUILT_FOR=\"${Python3_EXECUTABLE}\"")
  endif()
  if(TARGET TBB::tbb)
    target_link_libraries(${target} PRIVATE TBB::tbb)
    target_compile_definitions(${target} PRIVATE FLANGE_PYTHON_TBB)
  endif()
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${FP_NAME} LIBRARY_OUTPUT_DIRECTORY "${FP_OUTPUT_DIRECTORY}")
  # the `flange` package beside the module (its exceptions and result
  # types), copied once per output directory
  string(MD5 dir_id "${FP_OUTPUT_DIRECTORY}")
  set(package flange_python_package_${dir_id})
  if(NOT TARGET ${package})
    _flange_python_launcher("${FP_OUTPUT_DIRECTORY}")
    add_custom_target(${package}
      COMMAND ${CMAKE_COMMAND} -E make_directory "${FP_OUTPUT_DIRECTORY}/flange"
      COMMAND ${CMAKE_COMMAND} -E copy_if_different "${_FLANGE_PYTHON_PACKAGE_DIR}/__init__.py"
              "${FP_OUTPUT_DIRECTORY}/flange/__init__.py"
      VERBATIM)
  endif()
  add_dependencies(${target} ${package})
endfunction()

function(flange_urdf_python_module)
  cmake_parse_arguments(FU "FLOATING_BASE;NO_LIMITS" "NAME;URDF;OUTPUT_DIRECTORY;STOP_STIFFNESS;STOP_DISSIPATION" "" ${ARGN})
  if(NOT FU_NAME OR NOT FU_URDF)
    message(FATAL_ERROR "flange_urdf_python_module: NAME and URDF are needed")
  endif()
  if(NOT TARGET flange::urdf)
    message(FATAL_ERROR "flange_urdf_python_module: flange-urdf is not built (it needs libtinyxml2-dev)")
  endif()
  set(floating "")
  foreach(flag FLOATING_BASE NO_LIMITS)
    if(FU_${flag})
      list(APPEND floating ${flag})
    endif()
  endforeach()
  foreach(value STOP_STIFFNESS STOP_DISSIPATION)
    if(DEFINED FU_${value})
      list(APPEND floating ${value} ${FU_${value}})
    endif()
  endforeach()
  set(out "")
  if(FU_OUTPUT_DIRECTORY)
    set(out OUTPUT_DIRECTORY "${FU_OUTPUT_DIRECTORY}")
  endif()
  # the header flange_urdf_scene generates for the target (cmake/flange_urdf.cmake)
  flange_add_python_module(NAME ${FU_NAME} FACTORY ${FU_NAME}::make_scene ${out}
                           SCENE "${CMAKE_CURRENT_BINARY_DIR}/flange_urdf/${FU_NAME}_python/${FU_NAME}.hpp")
  flange_urdf_scene(${FU_NAME}_python "${FU_URDF}" NAMESPACE ${FU_NAME} ${floating})
endfunction()
