# `bake --force` over an earlier, longer bake in another packing: the bake is staged and moved in whole, then
# the earlier bake's outputs it did not replace go (frames outside its range, the other packing's textures),
# and a user's files stay, in the folder and in frames/. A directory under an output's name, or a file where
# frames/ goes, stops the rerun before any change.
# Usage: cmake -DSIXWAY=sixway -DSCENE=bake_tiny_scene.json -DOUT=dir -P bake_force.cmake
file(REMOVE_RECURSE ${OUT})

# Bakes into ${OUT}; extra arguments follow.
function(run_bake)
  execute_process(COMMAND ${SIXWAY} bake --scene ${SCENE} --tile 16 --scattering single --out ${OUT} ${ARGN}
                  RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
  set(bake_code ${code} PARENT_SCOPE)
  string(STRIP "${err}" err)
  set(bake_err "${err}" PARENT_SCOPE)
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/expect_files.cmake)

# A refused rerun: one line naming `path` and `problem`, and the earlier bake as it was.
function(expect_refused path problem)
  run_bake(--frames 1 --force --packing rlt-bbf)
  if(bake_code EQUAL 0 OR NOT bake_err MATCHES "^sixway: error: ${OUT}/${path}: ${problem}$")
    message(FATAL_ERROR "${path}: expected one line '${path}: ${problem}', got exit ${bake_code}:\n${bake_err}")
  endif()
  file(SHA256 ${OUT}/flipbook.json sidecar)
  if(NOT sidecar STREQUAL first_sidecar)
    message(FATAL_ERROR "${path}: the refused rerun changed flipbook.json")
  endif()
  message(STATUS "refused: ${bake_err}")
endfunction()

set(unity flipbook.json)
foreach(texture A B)
  foreach(extension exr png tga)
    list(APPEND unity flipbook_${texture}.${extension} flipbook_${texture}.${extension}.meta)
  endforeach()
endforeach()
string(REPLACE "flipbook_A" "flipbook_RLT" rlt_bbf "${unity}")
string(REPLACE "flipbook_B" "flipbook_BBF" rlt_bbf "${rlt_bbf}")

run_bake(--frames 3 --validate)
if(NOT bake_code EQUAL 0 OR bake_err MATCHES "validation:")
  message(FATAL_ERROR "the first bake failed (${bake_code}): ${bake_err}")
endif()
file(SHA256 ${OUT}/flipbook.json first_sidecar)
file(WRITE ${OUT}/notes.txt "a user's file")
file(WRITE ${OUT}/frames/notes.txt "a user's file")
set(first ${unity} frames frames/frame_0000.exr frames/frame_0001.exr frames/frame_0002.exr frames/notes.txt
          notes.txt)
expect_files(${OUT} "first bake" ${first})

file(MAKE_DIRECTORY ${OUT}/frames/frame_0007.exr)
expect_refused(frames/frame_0007.exr "is a directory, not a regular file; not replaced")
file(REMOVE_RECURSE ${OUT}/frames/frame_0007.exr)
file(RENAME ${OUT}/frames ${OUT}/frames.moved)
file(WRITE ${OUT}/frames "a user's file")
expect_refused(frames "is a regular file, not a directory; not replaced")
file(REMOVE ${OUT}/frames)
file(RENAME ${OUT}/frames.moved ${OUT}/frames)
expect_files(${OUT} "refused reruns" ${first})

# One frame from frame 1, in the other packing.
run_bake(--first 1 --frames 1 --force --packing rlt-bbf --validate)
if(NOT bake_code EQUAL 0 OR bake_err MATCHES "validation:")
  message(FATAL_ERROR "the --force rerun failed (${bake_code}): ${bake_err}")
endif()
expect_files(${OUT} "shorter rerun" ${rlt_bbf} frames frames/frame_0001.exr frames/notes.txt notes.txt)
