#version 460
// The camera-facing quad of the smoke billboard: two triangles over the rectangle of the image plane that the
// lightmaps cover, placed at a view depth inside the volume and projected by the host (projectionMatrix of
// the whole frame · viewMatrix, src/render/projection.h) into params.clipCorners.
#extension GL_GOOGLE_include_directive : require
#include "sixway_shade_params.glsl"

void main() {
  const int corner[6] = int[](0, 1, 2, 0, 2, 3);
  gl_Position = params.clipCorners[corner[gl_VertexIndex]];
}
