# Runs a sixway command that must fail: exit code non-zero, and exactly one line on stderr that
# matches EXPECT (a regular expression). Usage:
#   cmake -DCOMMAND="sixway;sim;--scene;x.json" -DEXPECT="x.json: no such file" -P expect_error.cmake
#
# With -DUNLESS_RANGE_GIB=N the error is a device limit that the command exceeds on small devices only: where
# `sixway info` reports a storage buffer range of N GiB or more, the test says "within this device's limits"
# (the test's SKIP_REGULAR_EXPRESSION) and runs nothing.
if(DEFINED UNLESS_RANGE_GIB)
  list(GET COMMAND 0 sixway)
  execute_process(COMMAND ${sixway} info OUTPUT_VARIABLE info)
  if(info MATCHES "storage buffer range +([0-9]+)(\\.[0-9]+)? GiB" AND CMAKE_MATCH_1 GREATER_EQUAL UNLESS_RANGE_GIB)
    message(STATUS "storage buffer range ${CMAKE_MATCH_1} GiB: within this device's limits")
    return()
  endif()
endif()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
if(code EQUAL 0)
  message(FATAL_ERROR "expected a failure, got exit 0\nstdout: ${out}\nstderr: ${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
if(err MATCHES "\n")
  message(FATAL_ERROR "expected one line on stderr, got:\n${err}")
endif()
message(STATUS "exit ${code}: ${err}")
