# Installs flange from a fresh build tree into a staging prefix, then builds
# and runs tests/deploy against it with find_package(flange).
set(stage ${WORK}/stage)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${WORK}/flange -DFLANGE_BUILD_TESTS=OFF
                        -DFLANGE_BUILD_EXAMPLES=OFF -DFLANGE_BUILD_BENCHMARKS=OFF COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/flange COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${WORK}/flange --prefix ${stage} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/tests/deploy -B ${WORK}/consumer -DCMAKE_PREFIX_PATH=${stage}
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer/c COMMAND_ERROR_IS_FATAL ANY)
message(STATUS "installed flange builds and runs in a consumer project")
