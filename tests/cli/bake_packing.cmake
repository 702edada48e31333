# `bake --packing`. A bake in the rlt-bbf preset over an earlier Unity-packed bake (--force) leaves
# the RLT/BBF textures with their .meta files, a sidecar whose channels say where each one is, and none of
# the earlier A/B textures (a directory never holds two packings).
file(REMOVE_RECURSE ${OUT})
foreach(packing unity rlt-bbf)
  execute_process(COMMAND ${SIXWAY} bake --scene ${SCENE} --frames 1 --tile 16 --scattering single --out ${OUT}
                          --force --packing ${packing} --validate
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR err MATCHES "validation:")
    message(FATAL_ERROR "bake --packing ${packing} failed (${code}):\n${out}\n${err}")
  endif()
endforeach()
if(NOT out MATCHES "packing rlt-bbf: RLT = \\(Right, Left, Top, alpha\\), BBF = \\(Bottom, Back, Front, emissive\\)")
  message(FATAL_ERROR "bake did not name the packing:\n${out}")
endif()
foreach(f flipbook_RLT.exr flipbook_BBF.exr flipbook_RLT.png flipbook_BBF.tga flipbook_RLT.exr.meta flipbook.json)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "bake --packing rlt-bbf did not write ${f}")
  endif()
endforeach()
file(GLOB earlier ${OUT}/flipbook_A.* ${OUT}/flipbook_B.*)
if(earlier)
  message(FATAL_ERROR "the earlier packing's textures are left: ${earlier}")
endif()
file(READ ${OUT}/flipbook.json sidecar)
foreach(pair "right;RLT.R" "left;RLT.G" "top;RLT.B" "alpha;RLT.A" "bottom;BBF.R" "back;BBF.G" "front;BBF.B"
             "emissive;BBF.A")
  list(GET pair 0 channel)
  list(GET pair 1 expected)
  string(JSON actual GET "${sidecar}" channels ${channel})
  if(NOT actual STREQUAL expected)
    message(FATAL_ERROR "flipbook.json: channel ${channel} is ${actual}, expected ${expected}")
  endif()
endforeach()
