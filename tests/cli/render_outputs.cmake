# `sixway render` as a user runs it: 3 frames of the small scene in reference mode with --exr --video, validation
# on. Every promised output must exist: PNG and EXR per frame, timings.json with per-stage times, the contact
# sheet, the MP4 (ffmpeg is one of tools/deps.sh's packages); timings.json counts the faulty pixels of every
# frame (eval::imageFaults), none here.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 3 --out ${OUT} --mode reference --exr --video
                        --validate
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR err MATCHES "validation:")
  message(FATAL_ERROR "sixway render failed (${code}):\n${out}\n${err}")
endif()
foreach(f frame_0000.png frame_0002.png frame_0000.exr frame_0002.exr timings.json contact_sheet.png video.mp4)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "sixway render did not write ${f}:\n${out}")
  endif()
endforeach()
file(READ ${OUT}/timings.json timings)
foreach(stage "shade" "guide" "obstacles" "shadow maps" "sim/lbm")
  string(JSON ms GET "${timings}" median_stage_ms "${stage}")
  if(NOT ms GREATER 0)
    message(FATAL_ERROR "timings.json: stage \"${stage}\" has no time (${ms})")
  endif()
endforeach()
string(JSON faults GET "${timings}" pixel_faults total)
string(JSON counted LENGTH "${timings}" pixel_faults per_frame)
if(NOT faults EQUAL 0 OR NOT counted EQUAL 3)
  message(FATAL_ERROR "timings.json: pixel_faults should count 3 frames, none faulty: ${timings}")
endif()
# Nothing is left under a temporary name, and --force into the directory of a longer render leaves none of its
# frames behind, nor its video.
file(GLOB partial ${OUT}/.*partial)
if(partial)
  message(FATAL_ERROR "temporary files left behind: ${partial}")
endif()
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 1 --out ${OUT} --mode guide --force
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "sixway render --force failed (${code}):\n${out}\n${err}")
endif()
foreach(f frame_0001.png frame_0002.png frame_0001.exr frame_0002.exr video.mp4)
  if(EXISTS ${OUT}/${f})
    message(FATAL_ERROR "--force left ${f} of the earlier, longer render")
  endif()
endforeach()
