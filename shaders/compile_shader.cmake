# Compiles one shader for Vulkan 1.3, validates the SPIR-V with spirv-val, and writes it as a C
# header of 32-bit words. Any warning fails the build (glslangValidator has no -Werror of its own).
# DEFINES: comma-separated preprocessor macros of a variant (may be empty).
get_filename_component(spv ${OUTPUT} NAME_WE)
set(spv ${OUTPUT}.spv)
set(define_flags)
if(DEFINES)
  string(REPLACE "," ";" define_list "${DEFINES}")
  foreach(define IN LISTS define_list)
    list(APPEND define_flags -D${define})
  endforeach()
endif()
execute_process(
  COMMAND ${GLSLANG} --target-env vulkan1.3 -I${INCLUDE_DIR} ${define_flags} --depfile ${DEPFILE} -o ${spv} ${SOURCE}
  RESULT_VARIABLE result
  OUTPUT_VARIABLE out
  ERROR_VARIABLE out)
string(REPLACE "${SOURCE}\n" "" out "${out}")  # glslang echoes the file name on success
string(STRIP "${out}" out)
if(NOT result EQUAL 0 OR out MATCHES "WARNING|ERROR")
  file(REMOVE ${OUTPUT} ${spv})
  message(FATAL_ERROR "shader ${SOURCE} failed (warnings are errors):\n${out}")
endif()

execute_process(COMMAND ${SPIRV_VAL} --target-env vulkan1.3 ${spv} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT result EQUAL 0)
  file(REMOVE ${OUTPUT} ${spv})
  message(FATAL_ERROR "shader ${SOURCE}: glslang produced invalid SPIR-V:\n${out}")
endif()

file(READ ${spv} hex HEX)
# SPIR-V is a stream of little-endian words: bytes b0 b1 b2 b3 → 0xb3b2b1b0.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "(([^,]*,){8})" "\\1\n  " words "${words}")
file(WRITE ${OUTPUT} "// Generated from ${SOURCE}: do not edit.\n#include <cstdint>\nalignas(4) static const uint32_t ${SYMBOL}[] = {\n  ${words}\n};\n")
