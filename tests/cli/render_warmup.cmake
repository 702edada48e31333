# `render --warmup N` runs the scene's first N frames without writing them, so its first frame is the
# plain render's frame N (bit for bit: same simulation, camera and lights); the display transform changes the
# PNG, never the linear EXR; timings.json records the warm-up and the smoke's coverage. A scene's
# render.warmup_frames does the same for `eval --scene`.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 3 --out ${OUT}/plain --mode reference --exr
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the plain render failed (${code}): ${err}")
endif()
execute_process(COMMAND ${SIXWAY} render --scene ${SCENE} --frames 1 --out ${OUT}/warm --mode reference --exr
                        --warmup 2 --tone-map aces --exposure 1
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the render with a warm-up failed (${code}): ${err}")
endif()
if(NOT out MATCHES "warm-up 2/2" OR NOT out MATCHES "the smoke covers [0-9.]+% of the picture at least")
  message(FATAL_ERROR "the warm-up or the coverage was not reported:\n${out}")
endif()
file(SHA256 ${OUT}/plain/frame_0002.exr plain_exr)
file(SHA256 ${OUT}/warm/frame_0000.exr warm_exr)
if(NOT plain_exr STREQUAL warm_exr)
  message(FATAL_ERROR "frame 0 after a 2-frame warm-up differs from frame 2 of the plain render")
endif()
file(SHA256 ${OUT}/plain/frame_0002.png plain_png)
file(SHA256 ${OUT}/warm/frame_0000.png warm_png)
if(plain_png STREQUAL warm_png)
  message(FATAL_ERROR "--tone-map aces --exposure 1 left the PNG as it was")
endif()
file(READ ${OUT}/warm/timings.json timings)
string(JSON warmup GET "${timings}" warmup_frames)
string(JSON least GET "${timings}" coverage least_of_last_16)
string(JSON seconds GET "${timings}" frames 0 seconds)
if(NOT warmup EQUAL 2 OR NOT least GREATER 0 OR NOT seconds GREATER 0.09)
  message(FATAL_ERROR "timings.json: warmup_frames ${warmup}, coverage ${least}, first frame at ${seconds} s")
endif()

# `sixway eval --scene` honours the scene's warm-up the same way: its first evaluated frame is scene frame 2.
file(READ ${SCENE} scene)
string(JSON scene SET "${scene}" render warmup_frames 2)
file(WRITE ${OUT}/warm_scene.json "${scene}")
execute_process(COMMAND ${SIXWAY} eval --scene ${OUT}/warm_scene.json --frames 1 --spp 4 --report ${OUT}/eval.json
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT out MATCHES "1 frames after 2 of warm-up")
  message(FATAL_ERROR "eval of a scene with a warm-up failed (${code}):\n${out}\n${err}")
endif()
file(READ ${OUT}/eval.json report)
string(JSON scene_frame GET "${report}" per_frame 0 scene_frame)
string(JSON seconds GET "${report}" per_frame 0 seconds)
if(NOT scene_frame EQUAL 2 OR NOT seconds GREATER 0.29 OR seconds GREATER 0.31)
  message(FATAL_ERROR "eval's first frame is scene frame ${scene_frame} at ${seconds} s, expected 2 at 0.3 s")
endif()
