# `render --force` over an earlier render in which a name the render writes is a directory or a FIFO: the
# rerun stops with one line naming it, before any change, so the earlier render stays whole (its contact
# sheet, frames and timings untouched); once the name is a file again the rerun replaces everything.
# Usage: cmake -DSIXWAY=sixway -DSCENE=small_plume.json -DOUT=dir -P render_force_all_or_nothing.cmake
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 3 --out ${OUT} --mode reference
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the first render failed (${code}): ${err}")
endif()

# The hashes of the earlier render's images (named, not globbed: a FIFO among them would block the read).
function(hash_outputs result)
  set(hashes "")
  foreach(f contact_sheet.png frame_0000.png frame_0001.png frame_0002.png)
    if(NOT EXISTS ${OUT}/${f})
      message(FATAL_ERROR "${f} of the earlier render is gone")
    endif()
    file(SHA256 ${OUT}/${f} h)
    list(APPEND hashes ${h})
  endforeach()
  set(${result} "${hashes}" PARENT_SCOPE)
endfunction()

# A --force rerun of one frame must fail with one line matching `expect` and leave the earlier render as it was.
function(expect_untouched what expect)
  hash_outputs(before)
  execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 1 --out ${OUT} --mode guide --force
                  RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  if(code EQUAL 0 OR NOT err MATCHES "${expect}" OR err MATCHES "\n")
    message(FATAL_ERROR "${what}: expected a failure with one line matching '${expect}', got exit ${code}: ${err}")
  endif()
  hash_outputs(after)
  if(NOT after STREQUAL before)
    message(FATAL_ERROR "${what}: the earlier render changed (a half commit):\n${before}\n${after}")
  endif()
  file(GLOB staging ${OUT}/.render.*)
  if(staging)
    message(FATAL_ERROR "${what}: left ${staging}")
  endif()
  message(STATUS "${what}: exit ${code}: ${err}")
endfunction()

file(REMOVE ${OUT}/timings.json)
file(MAKE_DIRECTORY ${OUT}/timings.json)
expect_untouched("timings.json a directory" "${OUT}/timings.json: is a directory, not a regular file")
file(REMOVE_RECURSE ${OUT}/timings.json)

# A FIFO under a frame's name that the one-frame rerun would remove, not replace.
execute_process(COMMAND mkfifo ${OUT}/frame_0007.png RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "mkfifo failed")
endif()
expect_untouched("frame_0007.png a FIFO" "${OUT}/frame_0007.png: is a FIFO, not a regular file")
file(REMOVE ${OUT}/frame_0007.png)

execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 1 --out ${OUT} --mode guide --force
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the --force rerun failed (${code}): ${err}")
endif()
file(GLOB visible RELATIVE ${OUT} ${OUT}/* ${OUT}/.*)
list(SORT visible)
if(NOT visible STREQUAL "contact_sheet.png;frame_0000.png;timings.json")
  message(FATAL_ERROR "after the rerun: ${visible}")
endif()
