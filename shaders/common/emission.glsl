// The smoke's emission ramp: emitted colour as a function of temperature, interpolated linearly
// between keys and clamped at the ends (docs/scene-format.md, smoke.emission).
#ifndef SIXWAY_EMISSION_GLSL
#define SIXWAY_EMISSION_GLSL

const int kMaxRampKeys = 16;

// keys[i] = (temperature, r, g, b) with strictly increasing temperatures; 1 <= count <= kMaxRampKeys.
vec3 rampColor(vec4 keys[kMaxRampKeys], int count, float temperature) {
  vec3 color = keys[0].yzw;
  for (int k = 1; k < count; ++k) {
    if (temperature <= keys[k - 1].x) break;
    float s = clamp((temperature - keys[k - 1].x) / (keys[k].x - keys[k - 1].x), 0.0, 1.0);
    color = mix(keys[k - 1].yzw, keys[k].yzw, s);
  }
  return color;
}

// Rec. 709 luminance of a linear colour: the emissive lightmap channel is one luminance value.
float luminance(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

#endif
