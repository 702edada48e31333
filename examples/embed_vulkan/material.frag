#version 450
// The engine's own smoke material: Unity VFX Graph's six-way lighting ("Six Way Smoke Lit") of sixway's
// lightmaps in the RLT/BBF packing (docs/formats.md, "Packing presets"), written as an engine would, from
// the formula alone (docs/conventions.md, "Shading"): a light's transmission t = Σ d_i² w_i, w_i the
// positive-side map where d_i ≥ 0 and the negative-side one otherwise, times its irradiance / π (sixway's
// maps are in its bake normalisation: Unity's values times π); constant ambient L0 as (2/3)·L0·Σ of the six
// maps; premultiplied, blended "over".
layout(push_constant) uniform Push {
  vec4 clipCorners[4];
  vec4 toLight;
  vec4 irradiance;
  vec4 ambient;
} push;

layout(binding = 0) uniform sampler2D rlt;  // R right, G left, B top, A alpha
layout(binding = 1) uniform sampler2D bbf;  // R bottom, G back, B front, A emissive

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;

void main() {
  const float kPi = 3.14159265358979;
  vec4 first = texture(rlt, uv), second = texture(bbf, uv);
  vec3 positive = vec3(first.r, first.b, second.g);   // right, top, back
  vec3 negative = vec3(first.g, second.r, second.b);  // left, bottom, front
  vec3 d = push.toLight.xyz;
  float t = dot(d * d, mix(negative, positive, greaterThanEqual(d, vec3(0.0))));
  vec3 radiance = push.irradiance.rgb * t / kPi +
                  push.ambient.rgb * (2.0 / 3.0) * (dot(positive, vec3(1.0)) + dot(negative, vec3(1.0)));
  color = vec4(radiance, first.a);
}
