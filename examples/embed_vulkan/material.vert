#version 450
// The engine's own smoke material (material.frag): the quad of sixway's lightmaps, its world corners
// (SmokeRenderer::lightmaps) projected by the engine's camera on the host.
layout(push_constant) uniform Push {
  vec4 clipCorners[4];  // bottom-left, bottom-right, top-right, top-left
  vec4 toLight;         // the sun in the six-way frame (x camera right, y camera up, z away from the camera)
  vec4 irradiance;      // the sun's colour · intensity
  vec4 ambient;         // constant ambient radiance
} push;

layout(location = 0) out vec2 uv;

void main() {
  const int corner[6] = int[](0, 1, 2, 0, 2, 3);
  const vec2 uvs[4] = vec2[](vec2(0, 1), vec2(1, 1), vec2(1, 0), vec2(0, 0));  // texel row 0 along the top
  uv = uvs[corner[gl_VertexIndex]];
  gl_Position = push.clipCorners[corner[gl_VertexIndex]];
}
