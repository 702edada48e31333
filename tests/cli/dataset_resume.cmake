# `sixway dataset` as the workers of a batch job run it: worker 1 of 2 makes exactly its shard (validation on);
# run again, it keeps the shard it made (a resumed job); a config with another seed must not reuse or
# overwrite it without --force.
file(REMOVE_RECURSE ${OUT})
function(run_dataset config expect_code)
  execute_process(COMMAND ${SIXWAY} dataset --config ${config} --out ${OUT} --shard 1/2 ${ARGN}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expect_code OR err MATCHES "validation:")
    message(FATAL_ERROR "sixway dataset --config ${config}: exit ${code}, expected ${expect_code}:\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

run_dataset(${CONFIG} 0 --validate)
if(NOT out MATCHES "wrote shard_00001.safetensors.*wrote 1 shards" OR EXISTS ${OUT}/shard_00000.safetensors
   OR NOT EXISTS ${OUT}/shard_00001.safetensors OR NOT EXISTS ${OUT}/dataset.json)
  message(FATAL_ERROR "worker 1/2 must write shard_00001 and dataset.json only:\n${out}")
endif()
run_dataset(${CONFIG} 0)
if(NOT out MATCHES "0 to make, 1 already made")
  message(FATAL_ERROR "a second run must keep the shard:\n${out}")
endif()
run_dataset(${OTHER_CONFIG} 1)
if(NOT err MATCHES "dataset.json: was made from another config; pass --force")
  message(FATAL_ERROR "another config must not reuse the output:\n${err}")
endif()
