# A bad pipeline cache ($XDG_CACHE_HOME/sixway/pipelines-<uuid>.bin) costs the compile time it would save,
# never the command: a FIFO there (which blocked every command), a directory (which failed every command with
# "basic_filebuf::underflow"), a link to a FIFO and a file beyond the 256 MiB read cap are each left unread with
# one note on stderr, the command succeeds, and saving leaves a FIFO or directory as it is.
# Usage: cmake -DSIXWAY=sixway -DSCENE=small_plume.json -DOUT=dir -P pipeline_cache.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
set(cache_home ${OUT}/cache)

# Runs `sim` for one step with the cache under ${cache_home}; sets `stderr_text` and fails on a non-zero exit,
# a hang (60 s) or a validation message.
function(run_sim what)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=${cache_home}
                          ${SIXWAY} sim --scene ${SCENE} --steps 1 --validate
                  TIMEOUT 60 RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${what}: sim failed or hung (${code}): ${err}")
  endif()
  if(err MATCHES "validation:")
    message(FATAL_ERROR "${what}: validation messages: ${err}")
  endif()
  set(stderr_text "${err}" PARENT_SCOPE)
endfunction()

# The first run writes the cache, which gives its device-specific name.
run_sim("no cache yet")
file(GLOB caches ${cache_home}/sixway/pipelines-*.bin)
list(LENGTH caches count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "expected one pipeline cache under ${cache_home}/sixway, found '${caches}'")
endif()
set(cache ${caches})
run_sim("a good cache")
if(NOT stderr_text STREQUAL "")
  message(FATAL_ERROR "a good cache printed: ${stderr_text}")
endif()

# Runs with whatever is at the cache path now: exactly one stderr line, a note about the cache.
function(expect_one_note what)
  run_sim("${what}")
  string(STRIP "${stderr_text}" note)
  if(NOT note MATCHES "^sixway: note: pipeline cache .*pipelines-[0-9a-f]+\\.bin .*; starting without it$"
     OR note MATCHES "\n")
    message(FATAL_ERROR "${what}: expected one note about the pipeline cache, got: '${stderr_text}'")
  endif()
  message(STATUS "${what}: ${note}")
endfunction()

file(REMOVE ${cache})
execute_process(COMMAND mkfifo ${cache} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "mkfifo failed")
endif()
expect_one_note("a FIFO")
execute_process(COMMAND test -p ${cache} RESULT_VARIABLE still_fifo)
if(NOT still_fifo EQUAL 0)
  message(FATAL_ERROR "saving replaced the FIFO at the cache path")
endif()

file(REMOVE ${cache})
file(MAKE_DIRECTORY ${cache})
expect_one_note("a directory")
if(NOT IS_DIRECTORY ${cache})
  message(FATAL_ERROR "saving replaced the directory at the cache path")
endif()

file(REMOVE_RECURSE ${cache})
execute_process(COMMAND mkfifo ${OUT}/elsewhere.fifo)
file(CREATE_LINK ${OUT}/elsewhere.fifo ${cache} SYMBOLIC)
expect_one_note("a link to a FIFO")

# 300 MiB of holes: refused by its size, not read.
file(REMOVE ${cache})
execute_process(COMMAND truncate -s 300M ${cache} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "truncate failed")
endif()
expect_one_note("a 300 MiB file")
file(SIZE ${cache} size)
if(size GREATER 268435456)
  message(FATAL_ERROR "the oversized cache was not replaced by the command's own (${size} bytes)")
endif()
run_sim("the cache saved after the oversized one")
if(NOT stderr_text STREQUAL "")
  message(FATAL_ERROR "the cache saved after the oversized one printed: ${stderr_text}")
endif()
