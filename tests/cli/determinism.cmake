# Determinism: the same sixway command run twice with the same seed writes bit-identical files on
# the same device and driver. Usage:
#   cmake -DSIXWAY=... -DCOMMAND="render;--scene;s.json;..." -DOUT=dir [-DSKIP="timings.json"] -P determinism.cmake
# Runs `sixway COMMAND --out OUT/run_a` and `... --out OUT/run_b`, then compares every file of run_a with the
# file of the same name in run_b byte for byte (SKIP: names of files that hold measured times).
file(REMOVE_RECURSE ${OUT})
foreach(run run_a run_b)
  execute_process(COMMAND ${SIXWAY} ${COMMAND} --out ${OUT}/${run} RESULT_VARIABLE code OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR err MATCHES "validation:")
    message(FATAL_ERROR "sixway ${COMMAND} --out ${OUT}/${run} failed (${code}):\n${out}\n${err}")
  endif()
endforeach()

file(GLOB_RECURSE files_a RELATIVE ${OUT}/run_a ${OUT}/run_a/*)
file(GLOB_RECURSE files_b RELATIVE ${OUT}/run_b ${OUT}/run_b/*)
list(SORT files_a)
list(SORT files_b)
if(NOT files_a STREQUAL files_b)
  message(FATAL_ERROR "the runs wrote different files:\n  ${files_a}\n  ${files_b}")
endif()
set(compared 0)
set(differing "")
foreach(f ${files_a})
  get_filename_component(name ${f} NAME)
  list(FIND SKIP ${name} skipped)
  if(NOT skipped EQUAL -1)
    continue()
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/run_a/${f} ${OUT}/run_b/${f}
                  RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    list(APPEND differing ${f})
  endif()
  math(EXPR compared "${compared} + 1")
endforeach()
if(differing)
  message(FATAL_ERROR "not bit-identical between two runs: ${differing}")
endif()
if(compared LESS 2)
  message(FATAL_ERROR "only ${compared} files to compare: ${files_a}")
endif()
message(STATUS "${compared} files bit-identical: ${files_a}")
