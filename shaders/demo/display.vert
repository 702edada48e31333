#version 460
// One triangle that covers the draw's viewport; uv (0, 0) at its top-left corner, (1, 1) at the bottom-right.
layout(location = 0) out vec2 uv;

void main() {
  vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  uv = corner;
  gl_Position = vec4(2.0 * corner.x - 1.0, 1.0 - 2.0 * corner.y, 0.0, 1.0);
}
