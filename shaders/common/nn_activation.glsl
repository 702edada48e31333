// Activations of the network's layers, chosen by a specialization constant (src/nn/graph.h Activation).
#ifndef SIXWAY_NN_ACTIVATION_GLSL
#define SIXWAY_NN_ACTIVATION_GLSL

const int NN_ACT_NONE = 0;
const int NN_ACT_RELU = 1;
const int NN_ACT_LEAKY_RELU = 2;
const int NN_ACT_GELU = 3;  // exact (erf) form, as torch.nn.functional.gelu
const int NN_ACT_SILU = 4;

// erf by Abramowitz & Stegun 7.1.26 (absolute error below 1.5e-7).
vec4 nnErf(vec4 x) {
  const vec4 a = abs(x);
  const vec4 t = 1.0 / (1.0 + 0.3275911 * a);
  const vec4 poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  return sign(x) * (1.0 - poly * exp(-a * a));
}

vec4 nnActivate(vec4 x, int kind, float negativeSlope) {
  if (kind == NN_ACT_RELU) return max(x, vec4(0.0));
  if (kind == NN_ACT_LEAKY_RELU) return mix(x * negativeSlope, x, greaterThanEqual(x, vec4(0.0)));
  if (kind == NN_ACT_GELU) return 0.5 * x * (1.0 + nnErf(x * 0.70710678118654752));
  if (kind == NN_ACT_SILU) return x / (1.0 + exp(-x));
  return x;
}

#endif
