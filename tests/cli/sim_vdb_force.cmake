# `sim --vdb-out DIR --force` over an earlier, longer run of the same scene: the new run's frames (the smoke's
# VDB and the obstacles' OBJ) replace the earlier ones, and the earlier run's later frames go; other files (a user's, another scene's frames) stay. A
# directory under a frame's name stops the rerun before any change.
# Usage: cmake -DSIXWAY=sixway -DSCENE=small_plume.json -DOUT=dir -P sim_vdb_force.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
file(READ ${SCENE} scene)
string(JSON name GET "${scene}" name)
# Frames short enough that the scene's steps_per_frame (4) rules, not the inflow's step rule.
string(REGEX REPLACE "\"frame_dt\": [0-9.]+" "\"frame_dt\": 0.002" scene "${scene}")
file(WRITE ${OUT}/scene.json "${scene}")
set(vdb ${OUT}/vdb)

# Runs `sim` for `steps` (4 a frame) into ${vdb}; extra arguments follow.
function(run_sim steps)
  execute_process(COMMAND ${SIXWAY} sim --scene ${OUT}/scene.json --steps ${steps} --vdb-out ${vdb} ${ARGN}
                  RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
  set(sim_code ${code} PARENT_SCOPE)
  set(sim_err "${err}" PARENT_SCOPE)
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/expect_files.cmake)

run_sim(12)
if(NOT sim_code EQUAL 0)
  message(FATAL_ERROR "the first run failed (${sim_code}): ${sim_err}")
endif()
file(WRITE ${vdb}/notes.txt "a user's file")
file(COPY_FILE ${vdb}/${name}_0003.vdb ${vdb}/other_scene_0003.vdb)

# A directory under a frame's name: refused before any change.
file(MAKE_DIRECTORY ${vdb}/${name}_0009.vdb)
run_sim(4 --force)
string(STRIP "${sim_err}" sim_err)
if(sim_code EQUAL 0 OR NOT sim_err MATCHES "${name}_0009.vdb: is a directory, not a regular file; not replaced$" OR sim_err MATCHES "\n")
  message(FATAL_ERROR "a directory under a frame's name: expected one line naming it, got exit ${sim_code}: ${sim_err}")
endif()
expect_files(${vdb} "refused rerun" ${name}_0001.obj ${name}_0001.vdb ${name}_0002.obj ${name}_0002.vdb
             ${name}_0003.obj ${name}_0003.vdb ${name}_0009.vdb notes.txt other_scene_0003.vdb)
file(REMOVE_RECURSE ${vdb}/${name}_0009.vdb)

# One frame over three: frames 2 and 3 of the earlier run go.
run_sim(4 --force --validate)
if(NOT sim_code EQUAL 0 OR sim_err MATCHES "validation:")
  message(FATAL_ERROR "the --force rerun failed (${sim_code}): ${sim_err}")
endif()
expect_files(${vdb} "shorter rerun" ${name}_0001.obj ${name}_0001.vdb notes.txt other_scene_0003.vdb)
