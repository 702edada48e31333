# `render --force` into an earlier render's directory. A rerun killed half-way leaves the earlier
# render as it was (no mix of old and new frames); a finished rerun replaces what sixway wrote and nothing else.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 3 --out ${OUT} --mode reference
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the first render failed (${code}): ${err}")
endif()
file(WRITE ${OUT}/frame_notes.txt "a user's file")
file(WRITE ${OUT}/frame_001.png "not a name sixway writes")
file(SHA256 ${OUT}/frame_0002.png frame_before)
file(SHA256 ${OUT}/timings.json timings_before)

# Killed after a few seconds, long before its 5,000 frames are done.
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 5000 --out ${OUT} --mode guide --force
                TIMEOUT 4 RESULT_VARIABLE code OUTPUT_QUIET ERROR_QUIET)
if(code EQUAL 0)
  message(FATAL_ERROR "the render meant to be killed finished")
endif()
file(GLOB visible RELATIVE ${OUT} ${OUT}/[a-z]*)
list(SORT visible)
set(expected contact_sheet.png frame_0000.png frame_0001.png frame_0002.png frame_001.png frame_notes.txt
    timings.json)
if(NOT visible STREQUAL expected)
  message(FATAL_ERROR "a killed --force rerun changed the directory: ${visible}")
endif()
file(SHA256 ${OUT}/frame_0002.png frame_after)
file(SHA256 ${OUT}/timings.json timings_after)
if(NOT frame_after STREQUAL frame_before OR NOT timings_after STREQUAL timings_before)
  message(FATAL_ERROR "a killed --force rerun changed the earlier render's files")
endif()

file(GLOB staging ${OUT}/.render.*.partial)
if(NOT staging)
  message(FATAL_ERROR "the killed render left no staging directory: was it killed before it wrote anything?")
endif()

# A killed process can take a while to end (NVIDIA's driver releases the GPU first) and until then its staging
# directory is a live render's: wait for it, up to 30 s. A zombie has ended: its parent (CMake) may not have
# collected it yet. On NVIDIA's driver the process still existed after 30 s, in a state not recorded then.
string(REGEX REPLACE ".*\\.render\\.([0-9]+)\\.partial$" "\\1" killed_pid "${staging}")
foreach(attempt RANGE 150)
  if(NOT EXISTS /proc/${killed_pid}/stat)
    break()
  endif()
  file(READ /proc/${killed_pid}/stat stat)
  if(stat MATCHES "\\) Z ")
    break()
  endif()
  execute_process(COMMAND sleep 0.2)
endforeach()
set(killed_state "ended")
if(EXISTS /proc/${killed_pid}/stat)
  file(READ /proc/${killed_pid}/stat killed_state)
endif()

# Finished: one frame replaces three; the user's files stay; the killed run's staging directory is removed.
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 1 --out ${OUT} --mode guide --force
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the --force rerun failed (${code}): ${err}")
endif()
file(GLOB visible RELATIVE ${OUT} ${OUT}/* ${OUT}/.*)
list(SORT visible)
set(expected contact_sheet.png frame_0000.png frame_001.png frame_notes.txt timings.json)
if(NOT visible STREQUAL expected)
  message(FATAL_ERROR "after a finished --force rerun: ${visible}, expected ${expected} (killed render: ${killed_state})")
endif()
file(READ ${OUT}/timings.json timings)
string(JSON mode GET "${timings}" mode)
if(NOT mode STREQUAL "guide")
  message(FATAL_ERROR "timings.json is not the new render's (mode ${mode})")
endif()
