# sixway-demo on a played-back VDB scene in a virtual X server: exit 0, no validation message, and the
# screenshots show the frames play (the first, empty frame differs from a later one; reset goes back to it).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
configure_file(${SCRIPT_IN} ${OUT}/session.txt @ONLY)
execute_process(
  COMMAND xvfb-run -a -s "-screen 0 640x480x24" ${DEMO} --scene ${SCENE} --weights ${WEIGHTS}
          --script ${OUT}/session.txt --width 160 --height 120 --validate
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
if(NOT code EQUAL 0 OR "${out}${err}" MATCHES "validation:")
  message(FATAL_ERROR "sixway-demo exited with ${code}\nstdout: ${out}\nstderr: ${err}")
endif()
foreach(name 00_empty_frame 01_smoke 02_reference 03_reset)
  if(NOT EXISTS ${OUT}/${name}.png)
    message(FATAL_ERROR "no screenshot ${name}.png\nstdout: ${out}\nstderr: ${err}")
  endif()
  file(SHA256 ${OUT}/${name}.png ${name})
endforeach()
if(${00_empty_frame} STREQUAL ${01_smoke})
  message(FATAL_ERROR "the played frames did not change the image")
endif()
if(${01_smoke} STREQUAL ${02_reference})
  message(FATAL_ERROR "neural and reference modes drew the same image")
endif()
