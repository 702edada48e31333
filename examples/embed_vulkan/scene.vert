#version 450
// The example's own scene, made in the shader: a floor (2 triangles) and a box (12), flat normals per face.
layout(push_constant) uniform Push {
  mat4 viewProjection;
  vec4 boxCentreHalf;  // xyz centre, w half size
} push;

layout(location = 0) out vec3 normal;
layout(location = 1) out vec3 albedo;

const vec3 kCorners[8] = vec3[](vec3(-1, -1, -1), vec3(1, -1, -1), vec3(1, 1, -1), vec3(-1, 1, -1),
                                vec3(-1, -1, 1), vec3(1, -1, 1), vec3(1, 1, 1), vec3(-1, 1, 1));
// Two triangles per face, counter-clockwise seen from outside.
const int kBoxIndices[36] = int[](0, 3, 2, 0, 2, 1,  4, 5, 6, 4, 6, 7,  0, 4, 7, 0, 7, 3,
                                  1, 2, 6, 1, 6, 5,  0, 1, 5, 0, 5, 4,  3, 7, 6, 3, 6, 2);
const vec3 kFaceNormals[6] = vec3[](vec3(0, 0, -1), vec3(0, 0, 1), vec3(-1, 0, 0), vec3(1, 0, 0),
                                   vec3(0, -1, 0), vec3(0, 1, 0));
const vec2 kFloor[6] = vec2[](vec2(-1, -1), vec2(1, 1), vec2(1, -1), vec2(-1, -1), vec2(-1, 1), vec2(1, 1));

void main() {
  vec3 position;
  if (gl_VertexIndex < 6) {
    position = vec3(3.0 * kFloor[gl_VertexIndex].x, 0.0, 3.0 * kFloor[gl_VertexIndex].y);
    normal = vec3(0, 1, 0);
    albedo = vec3(0.45, 0.42, 0.38);
  } else {
    int i = gl_VertexIndex - 6;
    position = push.boxCentreHalf.xyz + push.boxCentreHalf.w * kCorners[kBoxIndices[i]];
    normal = kFaceNormals[i / 6];
    albedo = vec3(0.2, 0.35, 0.6);
  }
  gl_Position = push.viewProjection * vec4(position, 1.0);
}
