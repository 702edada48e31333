# cmake -DBUILD=… -DSOURCE=… -DWORK=… -DSCENE=… -DWEIGHTS=… -P consume.cmake
# Installs the build tree into WORK/prefix, then builds tests/package/consumer against it twice: through
# find_package(sixway) and through pkg-config, and runs both programs.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix COMMAND_ERROR_IS_FATAL ANY
                OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/consumer -B ${WORK}/consumer -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/prefix
                COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${WORK}/consumer/consumer ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)

file(GLOB_RECURSE pc_files ${WORK}/prefix/sixway.pc)
get_filename_component(pc_dir "${pc_files}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
execute_process(COMMAND pkg-config --cflags --libs sixway OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE
                COMMAND_ERROR_IS_FATAL ANY)
separate_arguments(flags UNIX_COMMAND "${flags}")
execute_process(COMMAND c++ -O1 ${SOURCE}/consumer/main.cpp -o ${WORK}/consumer_pc ${flags}
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer_pc ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)
