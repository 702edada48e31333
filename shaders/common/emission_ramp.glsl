// The smoke's emission ramp: emitted colour as a function of temperature, interpolated linearly between keys
// and clamped at the ends (docs/scene-format.md, smoke.emission). The includer defines RAMP_KEYS, its uniform
// array of kMaxRampKeys (temperature, r, g, b) keys with strictly increasing temperatures, before including
// this file: the keys are read in place, since an array passed as a function argument is copied whole on
// every call, which llvmpipe does not optimise away (the guide's emission march took 2.5× as long with the copy).
#ifndef SIXWAY_EMISSION_RAMP_GLSL
#define SIXWAY_EMISSION_RAMP_GLSL

#include "emission.glsl"

#ifndef RAMP_KEYS
#error "define RAMP_KEYS (the uniform array of the ramp's keys) before including emission_ramp.glsl"
#endif

// 1 <= count <= kMaxRampKeys.
vec3 rampColor(int count, float temperature) {
  vec3 color = RAMP_KEYS[0].yzw;
  for (int k = 1; k < count; ++k) {
    if (temperature <= RAMP_KEYS[k - 1].x) break;
    float s = clamp((temperature - RAMP_KEYS[k - 1].x) / (RAMP_KEYS[k].x - RAMP_KEYS[k - 1].x), 0.0, 1.0);
    color = mix(RAMP_KEYS[k - 1].yzw, RAMP_KEYS[k].yzw, s);
  }
  return color;
}

#endif
