#version 460
// The demo's view of one image of the frame pipeline, into an 8-bit display image:
//   kind 0  a frame (linear RGB, the background already under the smoke), times the exposure
//   kind 1  a guiding map: R guide light (times the exposure), G alpha, B shell depth
//   kind 2  one channel of an image as grey (light channels times the exposure, alpha as it is)
// The display image holds sRGB codes: encoded here when its format is UNORM (kEncodeSrgb), by the hardware
// when it is an _SRGB format.
layout(constant_id = 0) const bool kEncodeSrgb = true;

layout(binding = 0) uniform sampler2D source;
layout(push_constant) uniform DisplayPush {
  int kind;
  int channel;          // kind 2: 0..3
  float exposure;
  int channelIsLight;   // kind 2: scale by the exposure
}
push;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;

// IEC 61966-2-1.
vec3 encodeSrgb(vec3 linear) {
  vec3 c = clamp(linear, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
  vec4 texel = texture(source, uv);
  vec3 rgb;
  if (push.kind == 0) {
    rgb = texel.rgb * push.exposure;
  } else if (push.kind == 1) {
    rgb = vec3(texel.r * push.exposure, texel.g, texel.b);
  } else {
    float value = texel[push.channel];
    rgb = vec3(push.channelIsLight != 0 ? value * push.exposure : value);
  }
  color = vec4(kEncodeSrgb ? encodeSrgb(rgb) : clamp(rgb, 0.0, 1.0), 1.0);
}
