# Shaders of the neural lightmaps (src/nn): one per operator, each also built as an NN_FP16 variant whose
# feature maps are stored as RGBA16F (arithmetic stays fp32).
foreach(nn_shader conv2d conv_transpose2x2 upsample_bilinear naf_norm_expand naf_dw_gate naf_tail input output)
  list(APPEND SIXWAY_SHADERS nn/${nn_shader}.comp nn/${nn_shader}.comp:NN_FP16)
endforeach()
list(APPEND SIXWAY_SHADERS nn/naf_attention.comp)
# Conv2d on cooperative matrices (NVIDIA's tensor cores): fp16 maps only.
list(APPEND SIXWAY_SHADERS nn/conv2d_matrix.comp:NN_FP16)
