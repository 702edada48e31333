# `sixway eval --dataset` as a user runs it: the tiny dataset (tools/datasets/tiny.json) generated, then every
# split of it evaluated with the fixed test network, validation on. The report must hold each split with its
# sample count and finite PSNRs.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${SIXWAY} dataset --config ${CONFIG} --out ${OUT}/dataset
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "sixway dataset failed (${code}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${SIXWAY} eval --dataset ${OUT}/dataset --weights ${WEIGHTS} --report ${OUT}/eval.json
                        --split train heldout_sequence heldout_camera --validate
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR err MATCHES "validation:")
  message(FATAL_ERROR "sixway eval failed (${code}):\n${out}\n${err}")
endif()
file(READ ${OUT}/eval.json report)
foreach(split train heldout_sequence heldout_camera)
  string(JSON samples GET "${report}" splits ${split} samples)
  string(JSON psnr GET "${report}" splits ${split} psnr_masked_db)
  if(NOT samples GREATER 0 OR NOT psnr GREATER 0)
    message(FATAL_ERROR "eval.json: split ${split}: ${samples} samples, PSNR ${psnr}")
  endif()
endforeach()

# A shard that dataset.json lists but that is gone is one line, not a silently smaller split.
file(GLOB shards ${OUT}/dataset/shard_*.safetensors)
list(SORT shards)
list(GET shards -1 last)
file(RENAME ${last} ${last}.moved)
execute_process(COMMAND ${SIXWAY} eval --dataset ${OUT}/dataset --weights ${WEIGHTS} --report ${OUT}/eval_missing.json
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(RENAME ${last}.moved ${last})
get_filename_component(name ${last} NAME)
if(code EQUAL 0 OR NOT err MATCHES "${name}: missing: dataset.json lists")
  message(FATAL_ERROR "eval with ${name} missing: exit ${code}, stderr: ${err}")
endif()
