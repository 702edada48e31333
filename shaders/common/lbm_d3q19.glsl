// D3Q19 lattice Boltzmann: velocity set, equilibrium, and the regularized BGK collision with a
// Smagorinsky eddy viscosity and Guo forcing. Lattice units throughout (dx = dt = 1, c_s² = 1/3).
// Needs GL_EXT_control_flow_attributes in the including shader.
#ifndef SIXWAY_LBM_D3Q19_GLSL
#define SIXWAY_LBM_D3Q19_GLSL

const int Q = 19;
// Pairs (i, i+1) are opposite for odd i: opposite(i) = i + 1 for odd i, i − 1 for even i > 0.
const ivec3 C[Q] = ivec3[](ivec3(0, 0, 0),
                           ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
                           ivec3(0, 0, 1), ivec3(0, 0, -1),
                           ivec3(1, 1, 0), ivec3(-1, -1, 0), ivec3(1, 0, 1), ivec3(-1, 0, -1),
                           ivec3(0, 1, 1), ivec3(0, -1, -1), ivec3(1, -1, 0), ivec3(-1, 1, 0),
                           ivec3(1, 0, -1), ivec3(-1, 0, 1), ivec3(0, 1, -1), ivec3(0, -1, 1));
const float W[Q] = float[](1.0 / 3.0,
                           1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0,
                           1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0,
                           1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0);

int opposite(int i) { return i == 0 ? 0 : ((i & 1) == 1 ? i + 1 : i - 1); }

// Second-order equilibrium: w ρ (1 + 3 c·u + 9/2 (c·u)² − 3/2 u²).
float equilibrium(int i, float rho, vec3 u) {
  float cu = dot(vec3(C[i]), u);
  return W[i] * rho * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * dot(u, u));
}

// Symmetric 3×3 tensor as (xx, yy, zz) and (xy, xz, yz).
struct Sym3 {
  vec3 d;
  vec3 o;
};

float contract(Sym3 a, ivec3 c) {  // (c c − c_s² I) : a
  vec3 cf = vec3(c);
  return dot(cf * cf - 1.0 / 3.0, a.d) + 2.0 * (cf.x * cf.y * a.o.x + cf.x * cf.z * a.o.y + cf.y * cf.z * a.o.z);
}

struct Macro {
  float rho;
  vec3 u;   // with the half-force shift of Guo et al. (2002)
  Sym3 pi;  // non-equilibrium momentum flux Π⁽¹⁾ = Σ c c (f − f_eq)
};

Macro moments(float f[Q], vec3 force) {
  float rho = 0.0;
  vec3 j = vec3(0.0);
  Sym3 m = Sym3(vec3(0.0), vec3(0.0));
  // Unrolled, so that f[] stays in registers (a dynamically indexed array goes to scratch memory).
  [[unroll]] for (int i = 0; i < Q; ++i) {
    vec3 c = vec3(C[i]);
    rho += f[i];
    j += f[i] * c;
    m.d += f[i] * c * c;
    m.o += f[i] * vec3(c.x * c.y, c.x * c.z, c.y * c.z);
  }
  Macro r;
  r.rho = rho;
  r.u = (j + 0.5 * force) / rho;
  // Π⁽¹⁾ = Σ c c f − ρ c_s² I − ρ u u: the regularized collision rebuilds f^neq from exactly this,
  // so that with τ it relaxes like Guo-forced BGK.
  vec3 u = r.u;
  r.pi.d = m.d - rho / 3.0 - rho * u * u;
  r.pi.o = m.o - rho * vec3(u.x * u.y, u.x * u.z, u.y * u.z);
  return r;
}

// Relaxation time with the Smagorinsky eddy viscosity ν_t = (C_s Δ)² |S|, solved in closed form
// from the non-equilibrium flux (Hou et al. 1996): τ = ½ (τ₀ + sqrt(τ₀² + 18 √2 C_s² |Π| / ρ)).
// With Guo forcing the strain is proportional to Π⁽¹⁾ + ½(F u + u F), not to Π⁽¹⁾ alone.
float effectiveTau(float tau0, float smagorinsky, Macro m, vec3 force) {
  if (smagorinsky == 0.0) return tau0;
  vec3 u = m.u;
  vec3 d = m.pi.d + force * u;
  vec3 o = m.pi.o + 0.5 * vec3(force.x * u.y + u.x * force.y, force.x * u.z + u.x * force.z,
                               force.y * u.z + u.y * force.z);
  float norm = sqrt(dot(d, d) + 2.0 * dot(o, o));
  return 0.5 * (tau0 + sqrt(tau0 * tau0 + 18.0 * 1.41421356 * smagorinsky * smagorinsky * norm / m.rho));
}

// Regularized BGK (Latt & Chopard 2006): the non-equilibrium part is rebuilt from its Hermite
// moments, f_i^neq = w_i [c_i·j^neq / c_s² + Q_i : Π⁽¹⁾ / (2 c_s⁴)], which removes the ghost modes that
// make plain BGK unstable at τ → ½; plus Guo's forcing term (1 − 1/(2τ)) S_i. With the half-force
// velocity shift j^neq = Σ c (f − f_eq) = −F/2; dropping it would add (3/2 − 1/(2τ)) F of momentum per
// step instead of F (a Poiseuille flow at τ = 0.6 then reaches only two thirds of its speed).
float collide(int i, Macro m, float tau, vec3 force) {
  vec3 c = vec3(C[i]);
  float cu = dot(c, m.u);
  float source = W[i] * dot(3.0 * (c - m.u) + 9.0 * cu * c, force);
  float fneq = W[i] * (4.5 * contract(m.pi, C[i]) - 1.5 * dot(c, force));
  return equilibrium(i, m.rho, m.u) + (1.0 - 1.0 / tau) * fneq + (1.0 - 0.5 / tau) * source;
}

#endif
