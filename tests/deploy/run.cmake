# Installs flange from a fresh build tree into a staging prefix, then builds
# and runs tests/deploy against it with find_package(flange).
set(stage ${WORK}/stage)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/flange -DFLANGE_BUILD_TESTS=OFF
                        -DFLANGE_BUILD_EXAMPLES=OFF -DFLANGE_BUILD_BENCHMARKS=OFF COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/flange COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${WORK}/flange --prefix ${stage} COMMAND_ERROR_IS_FATAL ANY)
set(python_args "")
if(PYTHON)
  set(python_args -DPython3_EXECUTABLE=${PYTHON})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/tests/deploy -B ${WORK}/consumer -DCMAKE_PREFIX_PATH=${stage}
                        ${python_args} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer/c COMMAND_ERROR_IS_FATAL ANY)
if(PYTHON)
  # the module, with the installed `flange` package beside it: at φ = 0 the
  # pendulum's rod is level, so φ̈ = −g/L = −9.81 1/s²
  # run by the launcher the installed flange_add_python_module writes beside it
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=PYTHONPATH ${WORK}/consumer/python/python3 -c
                          "import deployed, flange; d = deployed.derivative(0.0, deployed.initial_state()); assert abs(d[1] + 9.81) < 1e-12, d; print('python module from the installed flange:', d)"
                  COMMAND_ERROR_IS_FATAL ANY)
endif()
message(STATUS "installed flange builds and runs in a consumer project")
