#version 460
// A screen-aligned rectangle from two triangles, corners given in clip space (+y up).
#extension GL_GOOGLE_include_directive : require
#include "fill_gradient_push.glsl"

void main() {
  const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
  gl_Position = vec4(mix(push.clipMin, push.clipMax, corners[gl_VertexIndex]), 0.0, 1.0);
}
