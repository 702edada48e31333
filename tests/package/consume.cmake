# cmake -DBUILD=… -DSOURCE=… -DWORK=… -DSCENE=… -DWEIGHTS=… -P consume.cmake
# Installs the build tree into WORK/prefix, then builds tests/package/consumer's C++ and C programs against it
# twice, through find_package(sixway) and through pkg-config, and runs all four.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix COMMAND_ERROR_IS_FATAL ANY
                OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/consumer -B ${WORK}/consumer -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/prefix
                COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer COMMAND_ERROR_IS_FATAL ANY OUTPUT_QUIET)
execute_process(COMMAND ${WORK}/consumer/consumer ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer/consumer_c ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)

file(GLOB_RECURSE pc_files ${WORK}/prefix/sixway.pc)
get_filename_component(pc_dir "${pc_files}" DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
execute_process(COMMAND pkg-config --cflags sixway OUTPUT_VARIABLE cflags OUTPUT_STRIP_TRAILING_WHITESPACE
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND pkg-config --libs sixway OUTPUT_VARIABLE libs OUTPUT_STRIP_TRAILING_WHITESPACE
                COMMAND_ERROR_IS_FATAL ANY)
separate_arguments(cflags UNIX_COMMAND "${cflags}")
separate_arguments(libs UNIX_COMMAND "${libs}")
execute_process(COMMAND c++ -std=c++20 -O1 ${cflags} ${SOURCE}/consumer/main.cpp -o ${WORK}/consumer_pc ${libs}
                COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer_pc ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND cc -std=c99 -pedantic -Wall -Werror ${cflags} -c ${SOURCE}/consumer/main.c
                        -o ${WORK}/consumer_c.o COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND cc ${WORK}/consumer_c.o -o ${WORK}/consumer_c_pc ${libs} COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${WORK}/consumer_c_pc ${SCENE} ${WEIGHTS} COMMAND_ERROR_IS_FATAL ANY)
