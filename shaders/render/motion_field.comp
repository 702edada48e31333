#version 460
// The screen-space motion of the smoke over the billboard (docs/dataset-format.md, "Motion field"): per
// pixel of the guiding map, the smoke shell's world point p (the pixel's ray at the shell depth of the
// guide's B channel, decoded with the volume's depth range), the flow velocity there (trilinear in the
// lattice's velocity buffer), and the displacement in billboard pixels that carried the smoke to p over
// the interval: motion = pixel(p) − pixel(p − d), d = velocity · metres per velocity unit. x to the right,
// y downward (the row index). Zero where the guide has no shell (B = 1).
#extension GL_GOOGLE_include_directive : require
#include "depth.glsl"
#include "volume.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer MotionParams {
  CameraRays camera;    // the billboard's rays (plane = billboardBounds of the volume box)
  VolumeGrid velocity;  // the lattice of the velocity buffer
  vec4 shell;           // x, y: near and far view depths of the shell encoding; z: metres per velocity unit
  ivec4 image;          // xy: pixels of the guide and the motion field
}
params;
layout(binding = 1, rgba16f) uniform readonly image2D guide;
layout(std430, binding = 2) readonly buffer Velocity { vec4 velocity[]; };  // xyz per lattice cell
layout(std430, binding = 3) writeonly buffer Motion { vec2 motion[]; };

// The image-plane point q (distance 1, x right, y up) in billboard pixels (row 0 at the top).
vec2 pixelOf(vec2 q) {
  vec4 plane = params.camera.plane;
  return vec2((q.x - plane.x) / (plane.z - plane.x), (plane.w - q.y) / (plane.w - plane.y)) *
         vec2(params.image.xy);
}

// The image-plane point of world point x; w = 0 when x is not in front of the camera.
vec3 project(vec3 x) {
  vec3 v = x - params.camera.position.xyz;
  float z = dot(v, params.camera.forward.xyz);
  if (z <= 0.0) return vec3(0.0);
  return vec3(dot(v, params.camera.right.xyz) / z, dot(v, params.camera.up.xyz) / z, 1.0);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, params.image.xy))) return;
  uint index = uint(pixel.y * params.image.x + pixel.x);
  float encoded = imageLoad(guide, pixel).b;
  if (encoded >= 1.0) {
    motion[index] = vec2(0.0);
    return;
  }
  vec2 uv = (vec2(pixel) + 0.5) / vec2(params.image.xy);
  vec4 plane = params.camera.plane;
  vec2 q = vec2(mix(plane.x, plane.z, uv.x), mix(plane.w, plane.y, uv.y));
  vec3 p = worldAtViewDepth(params.camera, q, decodeShellDepth(encoded, params.shell.xy));

  vec3 d = vec3(0.0);
  if (insideVolume(params.velocity, p)) {
    Lerp8 l = lerp8(params.velocity.size.xyz, volumeSampleCoord(params.velocity, p));
    d = LERP8(velocity, l).xyz * params.shell.z;
  }
  // Smoke at rest (or outside the grid) moves by exactly zero, whatever the rounding of the projections.
  vec3 now = project(p), before = project(p - d);
  bool moves = any(notEqual(d, vec3(0.0))) && now.z > 0.0 && before.z > 0.0;
  motion[index] = moves ? pixelOf(now.xy) - pixelOf(before.xy) : vec2(0.0);
}
