# The showcase where the smoke has met the cylinder (scene frame 150, 512² frame, its own lightmap size: where a
# composite of the smoke as a card at its shell depth left black dots of the background beside the cylinder, 12
# pixels of them): no pixel may be non-finite, negative or in a dark dot (eval::imageFaults) in any method of
# `sixway eval` (the report's summary.image.METHOD.pixel_faults; its 1-sample truth is noise, not scanned). Its
# neural method is the renderer `sixway render` runs (modes::ModeRenderer), whose own count in timings.json
# cli.render_outputs checks. SCENE is assets/scenes/showcase.json.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
file(READ ${SCENE} scene)
string(JSON scene SET "${scene}" render warmup_frames 150)
file(WRITE ${OUT}/showcase_150.json "${scene}")

execute_process(COMMAND ${SIXWAY} eval --scene ${OUT}/showcase_150.json --frames 1 --spp 1 --no-equal-time
                        --report ${OUT}/eval.json --validate
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR err MATCHES "validation:")
  message(FATAL_ERROR "sixway eval failed (${code}):\n${out}\n${err}")
endif()
file(READ ${OUT}/eval.json report)
string(JSON methods LENGTH "${report}" methods)
math(EXPR last "${methods} - 1")
foreach(i RANGE ${last})
  string(JSON method GET "${report}" methods ${i})
  string(JSON faults GET "${report}" summary image ${method} pixel_faults)
  if(NOT faults EQUAL 0)
    message(FATAL_ERROR "sixway eval, ${method}: ${faults} faulty pixels\n${err}")
  endif()
endforeach()
