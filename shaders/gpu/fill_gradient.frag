#version 460
// Colour from the pixel position, premultiplied by alpha: a known image for testing the
// graphics path (pipeline creation, viewport orientation, specialization, blending).
#extension GL_GOOGLE_include_directive : require
#include "fill_gradient_push.glsl"

layout(constant_id = 0) const float BLUE = 0.25;
layout(location = 0) out vec4 color;

void main() {
  color = push.alpha * vec4(gl_FragCoord.xy / push.targetSize, BLUE, 1.0);
}
