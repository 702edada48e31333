// Specialization constant ids of the network's operators (shaders/nn): one id per constant name across the
// family, so that the host sets a constant by the same id in every shader. src/nn/nn_spec.h holds the same
// ids; gpu::Pipeline and tests/gpu/test_spec_contract.cpp check that the two agree.
#ifndef SIXWAY_NN_SPEC_GLSL
#define SIXWAY_NN_SPEC_GLSL

#define NN_SPEC_LOCAL_SIZE_X 0  // the workgroup size (local_size_x_id, local_size_y_id)
#define NN_SPEC_LOCAL_SIZE_Y 1
#define NN_SPEC_WIDTH 2  // the map an operator writes or normalizes
#define NN_SPEC_HEIGHT 3
#define NN_SPEC_IN_WIDTH 4
#define NN_SPEC_IN_HEIGHT 5
#define NN_SPEC_OUT_WIDTH 6
#define NN_SPEC_OUT_HEIGHT 7
#define NN_SPEC_CHANNELS 8
#define NN_SPEC_GATED_CHANNELS 9
#define NN_SPEC_FFN_CHANNELS 10
#define NN_SPEC_PROJECTION_CHANNELS 11
#define NN_SPEC_GROUPS 12
#define NN_SPEC_GROUPS_IN 13
#define NN_SPEC_GROUPS_A 14
#define NN_SPEC_GROUPS_B 15
#define NN_SPEC_PX 16  // output pixels per invocation along x and y
#define NN_SPEC_PY 17
#define NN_SPEC_KERNEL 18
#define NN_SPEC_STRIDE 19
#define NN_SPEC_SLICE 20
#define NN_SPEC_WEIGHT_VEC4S 21
#define NN_SPEC_ACTIVATION 22
#define NN_SPEC_NEGATIVE_SLOPE 23
#define NN_SPEC_EPS 24
#define NN_SPEC_FACTOR 25
#define NN_SPEC_PARTIAL_COUNT 26
#define NN_SPEC_PIXELS 27
#define NN_SPEC_GUIDE_WIDTH 28  // input.comp
#define NN_SPEC_GUIDE_HEIGHT 29
#define NN_SPEC_GUIDE_CHANNELS 30
#define NN_SPEC_MAP_WIDTH 31  // output.comp
#define NN_SPEC_MAP_HEIGHT 32
#define NN_SPEC_SRGB_MASK 33
#define NN_SPEC_SOURCE_0 34
#define NN_SPEC_SOURCE_1 35
#define NN_SPEC_SOURCE_2 36
#define NN_SPEC_SOURCE_3 37
#define NN_SPEC_SOURCE_4 38
#define NN_SPEC_SOURCE_5 39
#define NN_SPEC_SOURCE_6 40
#define NN_SPEC_SOURCE_7 41
#define NN_SPEC_A_0 42
#define NN_SPEC_A_1 43
#define NN_SPEC_A_2 44
#define NN_SPEC_A_3 45
#define NN_SPEC_B_0 46
#define NN_SPEC_B_1 47
#define NN_SPEC_B_2 48
#define NN_SPEC_B_3 49
#define NN_SPEC_ALBEDO_CHANNEL 50  // input.comp
#define NN_SPEC_MATRIX_M 51  // conv2d_matrix.comp
#define NN_SPEC_MATRIX_N 52
#define NN_SPEC_MATRIX_K 53
#define NN_SPEC_N_TILES 54
#define NN_SPEC_K_CHUNKS 55
#define NN_SPEC_N_PADDED 56
#define NN_SPEC_OUT_GROUPS 57

#endif
