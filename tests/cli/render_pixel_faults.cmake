# `sixway render` of the showcase where the smoke has met the cylinder (scene frame 150, 512² frame, 256²
# lightmaps: where a composite of the smoke as a card at its shell depth left black dots of the background beside
# the cylinder, 12 pixels of them), in the neural mode and the multiply-scattered flipbook's: no pixel may be
# non-finite, negative or in a dark dot (timings.json's pixel_faults, eval::imageFaults). SCENE is
# assets/scenes/showcase.json.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
file(READ ${SCENE} scene)
string(JSON scene SET "${scene}" render lightmap_size 256)
string(JSON scene SET "${scene}" render warmup_frames 150)
file(WRITE ${OUT}/showcase_150.json "${scene}")
foreach(mode neural traditional-ms)
  execute_process(COMMAND ${SIXWAY} render --scene ${OUT}/showcase_150.json --frames 1 --mode ${mode}
                          --out ${OUT}/${mode} --validate
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0 OR err MATCHES "validation:")
    message(FATAL_ERROR "sixway render --mode ${mode} failed (${code}):\n${out}\n${err}")
  endif()
  file(READ ${OUT}/${mode}/timings.json timings)
  string(JSON faults GET "${timings}" pixel_faults total)
  if(NOT faults EQUAL 0)
    string(JSON detail GET "${timings}" pixel_faults per_frame)
    message(FATAL_ERROR "sixway render --mode ${mode}: ${faults} faulty pixels: ${detail}\n${err}")
  endif()
endforeach()
