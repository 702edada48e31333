# Runs a sixway command that must fail: exit code non-zero, and exactly one line on stderr that
# matches EXPECT (a regular expression). Usage:
#   cmake -DCOMMAND="sixway;sim;--scene;x.json" -DEXPECT="x.json: no such file" -P expect_error.cmake
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
