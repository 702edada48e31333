// LayerNorm2d of NAFNet (Chen et al. 2022): per pixel, over its C channels, biased variance, eps inside the
// square root. `x` holds NN_LN_GROUPS channel groups; channels past NN_LN_CHANNELS are zero padding and stay
// out of the statistics. The caller defines NN_LN_GROUPS and NN_LN_CHANNELS (specialization constants).
#ifndef SIXWAY_NN_LAYER_NORM_GLSL
#define SIXWAY_NN_LAYER_NORM_GLSL

// 1 for the real channels of group g, 0 for its padding.
vec4 nnChannelMask(int g) {
  const int first = g * 4;
  return vec4(lessThan(ivec4(first, first + 1, first + 2, first + 3), ivec4(NN_LN_CHANNELS)));
}

// Normalises x in place (without the affine part): (x - mean) / sqrt(var + eps); padding stays 0.
void nnLayerNorm(inout vec4 x[NN_LN_GROUPS], float eps) {
  vec4 sum = vec4(0.0);
  [[unroll]] for (int g = 0; g < NN_LN_GROUPS; ++g) sum += x[g];
  const float mean = dot(sum, vec4(1.0)) / float(NN_LN_CHANNELS);
  vec4 squares = vec4(0.0);
  [[unroll]] for (int g = 0; g < NN_LN_GROUPS; ++g) {
    x[g] = (x[g] - mean) * nnChannelMask(g);
    squares += x[g] * x[g];
  }
  const float inverseDeviation = 1.0 / sqrt(dot(squares, vec4(1.0)) / float(NN_LN_CHANNELS) + eps);
  [[unroll]] for (int g = 0; g < NN_LN_GROUPS; ++g) x[g] *= inverseDeviation;
}

#endif
