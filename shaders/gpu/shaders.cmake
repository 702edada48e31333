# Shaders of the Vulkan host itself (src/gpu) and its tests.
list(APPEND SIXWAY_SHADERS
  gpu/reduce_stats.comp
  gpu/fill_gradient.vert
  gpu/fill_gradient.frag
  gpu/texel_buffer_scale.comp
  gpu/linear_index_probe.comp
  gpu/copy_words.comp
)
