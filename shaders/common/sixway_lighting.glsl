// Six-way lighting of premultiplied lightmaps (docs/conventions.md, "Shading"; Unity VFX Graph
// "Six Way Smoke Lit"; the conventions and the reasons for them are in docs/real-time-rendering.md,
// "Six-way shading").
// Lightmap values are in sixway's bake normalisation (1 = a white Lambertian surface facing a light of
// irradiance π); Unity's shader works in those values divided by π, which is why π appears below where Unity
// has none. Channels: rightTopBack = lightmap A.rgb, leftBottomFront = lightmap B.rgb.
#ifndef SIXWAY_LIGHTING_GLSL
#define SIXWAY_LIGHTING_GLSL

const float kPi = 3.14159265358979;
const int kMaxGradientKeys = 16;

// t = Σ_i d_i² w_i with w_i = A_i where d_i ≥ 0, else B_i: the squared weights of Unity (no clamp); `d` is
// the unit direction toward the light in the six-way frame (x camera right, y camera up, z away from it).
float sixWayTransmission(vec3 d, vec3 rightTopBack, vec3 leftBottomFront) {
  vec3 w = mix(leftBottomFront, rightTopBack, greaterThanEqual(d, vec3(0.0)));
  return dot(d * d, w);
}

// Unity's colour absorption: s_c = 1 + log2(max(1e-5, color_c)) / log2(0.2), T = pow(saturate(t/r), s_c)·r,
// with t and T in Unity's units (ours / π) and, for premultiplied lightmaps, the range r scaled by alpha
// (as Unity's premultiplied mode does). Returns T in our units. `range` = r = (1 − 1/π)·strength + 1/π.
vec3 absorbedTransmission(float t, float alpha, vec3 color, float range) {
  vec3 s = 1.0 + log2(max(vec3(1e-5), color)) / log2(0.2);
  float r = kPi * range * (alpha > 0.0 ? alpha : 1.0);
  return r * pow(vec3(clamp(t / r, 0.0, 1.0)), s);
}

// What a light's transmission t becomes: absorbed (Unity's absorption mode) or tinted (plain multiply).
vec3 lightResponse(float t, float alpha, vec3 color, float range, bool absorption) {
  return absorption ? absorbedTransmission(t, alpha, color, range) : t * color;
}

// Ambient light from L1 spherical harmonics of the radiance, L(w) = L0 + L1·w, with L1 already expressed in
// the six-way frame: sh[0] = L0, sh[1..3] = L1 along x, y, z (rgb each). Unity's formula
// (4π/6)·Σ_i [A_i (L0 + L1_i) + B_i (L0 − L1_i)] on Unity's lightmap values (ours / π) is
// (2/3)·Σ_i [...] on ours: the six-point quadrature of ∫ L(w) · lightmap(w) / π dw.
vec3 sixWayAmbient(vec3 rightTopBack, vec3 leftBottomFront, vec4 sh[4], float alpha, vec3 color, float range,
                   bool absorption) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 3; ++i) {
    vec3 plus = sh[0].rgb + sh[i + 1].rgb, minus = sh[0].rgb - sh[i + 1].rgb;
    sum += lightResponse(rightTopBack[i], alpha, color, range, absorption) * plus +
           lightResponse(leftBottomFront[i], alpha, color, range, absorption) * minus;
  }
  return (2.0 / 3.0) * sum;
}

// Unity's "Lightmap Remap" ranges on straight (not premultiplied) values: [in.x, in.y] → [0, 1] (clamped),
// then → [out.z, out.w], at least 0. range = (inMin, inMax, outMin, outMax).
vec3 remapRange(vec3 value, vec4 range) {
  vec3 unit = clamp((value - range.x) / (range.y - range.x), 0.0, 1.0);
  return max(vec3(0.0), mix(vec3(range.z), vec3(range.w), unit));
}

// The emissive colour of an emissive-channel value x ≥ 0 through a gradient of keys (position, r, g, b) with
// strictly increasing positions > 0: linear between keys; from black at 0 up to the first key; beyond the
// last key the last colour scaled by x / position (the channel is premultiplied and unbounded, so empty
// pixels stay black and bright ones keep growing, unlike Unity's clamped 8-bit gradient).
vec3 gradientColor(vec4 keys[kMaxGradientKeys], int count, float x) {
  x = max(x, 0.0);
  if (x <= keys[0].x) return keys[0].yzw * (x / keys[0].x);
  for (int k = 1; k < count; ++k)
    if (x <= keys[k].x) return mix(keys[k - 1].yzw, keys[k].yzw, (x - keys[k - 1].x) / (keys[k].x - keys[k - 1].x));
  return keys[count - 1].yzw * (x / keys[count - 1].x);
}

#endif
