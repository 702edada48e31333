// The smoke's emission: the ramp's key count and the luminance of an emitted colour
// (docs/scene-format.md, smoke.emission). The ramp itself is read by emission_ramp.glsl.
#ifndef SIXWAY_EMISSION_GLSL
#define SIXWAY_EMISSION_GLSL

const int kMaxRampKeys = 16;

// Rec. 709 luminance of a linear colour: the emissive lightmap channel is one luminance value.
float luminance(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

#endif
