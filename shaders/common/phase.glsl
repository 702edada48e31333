// The Henyey–Greenstein phase function (Henyey & Greenstein 1941), normalised to 1 over the sphere,
// in terms of the cosine of the angle between the propagation directions before and after scattering
// (g > 0: forward scattering).
#ifndef SIXWAY_PHASE_GLSL
#define SIXWAY_PHASE_GLSL

const float kPi = 3.14159265358979;

float hgPhase(float cosTheta, float g) {
  float denominator = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (4.0 * kPi * denominator * sqrt(denominator));
}

// Two unit vectors completing n to a right-handed orthonormal basis (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited").
void orthonormalBasis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// A new propagation direction after scattering from propagation direction w, distributed as
// hgPhase(dot(w, result), g), from two uniform numbers (inverse of the HG cumulative distribution).
vec3 hgSample(vec3 w, float g, vec2 xi) {
  float cosTheta;
  if (abs(g) < 1e-3) {
    cosTheta = 1.0 - 2.0 * xi.x;
  } else {
    float q = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi.x);
    cosTheta = clamp((1.0 + g * g - q * q) / (2.0 * g), -1.0, 1.0);
  }
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * kPi * xi.y;
  vec3 t, b;
  orthonormalBasis(w, t, b);
  return normalize(cosTheta * w + sinTheta * (cos(phi) * t + sin(phi) * b));
}

#endif
