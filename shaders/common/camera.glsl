// Rays of a pinhole camera through the pixels of an image that covers a rectangle of the image plane
// (src/render/camera.h). The rectangle is given at distance 1 in front of the camera, x right, y up;
// image row 0 is the top. The same mapping serves whole frames and billboards (src/render/billboard.h).
#ifndef SIXWAY_CAMERA_GLSL
#define SIXWAY_CAMERA_GLSL

struct CameraRays {
  vec4 position;  // xyz: the eye
  vec4 right;     // xyz: unit camera axes in world space
  vec4 up;
  vec4 forward;
  vec4 plane;  // xy: lower-left corner of the rectangle, zw: upper-right corner (image plane at distance 1)
};

// `pixel` in pixel units (x + 0.5, y + 0.5 is the centre of pixel (x, y)).
vec3 cameraRayDirection(CameraRays c, vec2 pixel, vec2 imageSize) {
  vec2 uv = pixel / imageSize;
  vec2 q = vec2(mix(c.plane.x, c.plane.z, uv.x), mix(c.plane.w, c.plane.y, uv.y));
  return normalize(c.forward.xyz + q.x * c.right.xyz + q.y * c.up.xyz);
}

#endif
