# `sim --vdb-out` names each frame's file "<scene name>_NNNN.vdb" whatever the name's length: a fixed buffer
# once cut names of 54 characters and more, and every frame overwrote one file without ".vdb".
# Usage: cmake -DSIXWAY=sixway -DSCENE=small_plume.json -DOUT=dir -P sim_vdb_long_name.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(name "a_plume_whose_name_runs_on_well_past_sixty_four_characters_of_the_old_buffer")
file(READ ${SCENE} scene)
string(REGEX REPLACE "\"name\": \"[^\"]*\"" "\"name\": \"${name}\"" scene "${scene}")
# Frames short enough that the scene's steps_per_frame (4) rules, not the inflow's step rule.
string(REGEX REPLACE "\"frame_dt\": [0-9.]+" "\"frame_dt\": 0.002" scene "${scene}")
file(WRITE ${OUT}/long_name.json "${scene}")
# 4 steps a frame: 12 steps are 3 frames.
execute_process(COMMAND ${SIXWAY} sim --scene ${OUT}/long_name.json --steps 12 --vdb-out ${OUT}/vdb --validate
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "sim failed (${code}): ${err}")
endif()
if(err MATCHES "validation:")
  message(FATAL_ERROR "validation messages: ${err}")
endif()
file(GLOB written RELATIVE ${OUT}/vdb ${OUT}/vdb/*)
list(SORT written)
set(expected ${name}_0001.obj ${name}_0001.vdb ${name}_0002.obj ${name}_0002.vdb ${name}_0003.obj ${name}_0003.vdb)
if(NOT written STREQUAL expected)
  message(FATAL_ERROR "sim --vdb-out wrote '${written}', expected '${expected}'")
endif()
message(STATUS "wrote ${written}")
