# glslang wrapper: compile one shader for Vulkan 1.3 into a C header of SPIR-V words,
# and fail the build on any warning (glslangValidator has no -Werror of its own).
execute_process(
  COMMAND ${GLSLANG} --target-env vulkan1.3 -I${INCLUDE_DIR} --depfile ${DEPFILE}
          --vn ${SYMBOL} -o ${OUTPUT} ${SOURCE}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE out
  ERROR_VARIABLE out)
string(REPLACE "${SOURCE}\n" "" out "${out}")  # glslang echoes the file name on success
string(STRIP "${out}" out)
if(NOT result EQUAL 0 OR out MATCHES "WARNING|ERROR")
  file(REMOVE ${OUTPUT})
  message(FATAL_ERROR "shader ${SOURCE} failed (warnings are errors):\n${out}")
endif()
