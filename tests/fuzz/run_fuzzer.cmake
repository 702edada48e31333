# Runs one fuzz target for SECONDS over its committed seeds (SEEDS, read only) and what earlier runs found
# (WORK/corpus), with the target's own libFuzzer FLAGS and LEAK_SUPPRESSIONS; a crash, hang (> 10 s per
# input), leak or sanitizer report fails with the input saved in WORK. libFuzzer's output (its final stats)
# is kept in WORK/last_run.log: CTest keeps a passed test's output only until its next run in the build.
file(MAKE_DIRECTORY ${WORK}/corpus)
if(LEAK_SUPPRESSIONS)
  set(ENV{LSAN_OPTIONS} "suppressions=${LEAK_SUPPRESSIONS}:print_suppressions=0")
endif()
execute_process(
  COMMAND ${FUZZER} ${WORK}/corpus ${SEEDS} -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048
          -artifact_prefix=${WORK}/ -print_final_stats=1 ${FLAGS}
  RESULT_VARIABLE result
  ERROR_VARIABLE output ECHO_ERROR_VARIABLE)
file(WRITE ${WORK}/last_run.log "${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${result}); the input is in ${WORK}/")
endif()
