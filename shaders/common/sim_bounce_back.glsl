// Bounce-back of populations from obstacle walls, shared by lbm_step.comp (the flow) and forces.comp
// (momentum exchange) so that force and flow see the same populations. Two rules:
//   half-way (Ladd 1994): the wall lies half-way along every link, f_i(x_f) = f*_ī(x_f) + 6 w_i ρ c_i·u_w;
//   interpolated (Bouzidi, Firdaouss & Lallemand 2001, Phys. Fluids 13, 3452, eqs. 5a and 5b): the wall lies
//   at the fraction q of the link from x_f toward x_f − c_i where it crosses the obstacle's analytic surface,
//   and the population is interpolated linearly along the link:
//     q < ½: f_i(x_f) = 2q f*_ī(x_f) + (1 − 2q) f*_ī(x_f + c_i)          + 6 w_i ρ c_i·u_w
//     q ≥ ½: f_i(x_f) = f*_ī(x_f)/(2q) + (2q − 1)/(2q) f*_i(x_f)          + 3 w_i ρ c_i·u_w / q
//   The moving-wall term is Ladd's, carried with the weight of the population reflected at the wall: 1 for
//   q < ½, 1/(2q) for q ≥ ½ (Bouzidi et al. 2001; Lallemand & Luo 2003, J. Comput. Phys. 184, 406).
//   Both agree with half-way at q = ½, which meshes and links without a known wall position use.
// The including shader declares: the specialization constant INTERPOLATED_BOUNCE_BACK (bool), the cell flags
// as `flags`, and `float awayFromWall(int i, ivec3 p)`: f*_i(p), the population fluid cell p sent along C[i]
// (away from the wall) in the step before; and includes lbm_in_place.glsl (the lattice) first.
#ifndef SIXWAY_SIM_BOUNCE_BACK_GLSL
#define SIXWAY_SIM_BOUNCE_BACK_GLSL

#include "lbm_d3q19.glsl"
#include "lbm_in_place.glsl"
#include "sim_grid.glsl"

// Parameter intervals [x, y] of the line m + t d (relative to the shape's centre) inside a shape's parts.
const vec2 EVERYWHERE = vec2(-1e30, 1e30);
const vec2 NOWHERE = vec2(1e30, -1e30);

vec2 slabInterval(float m, float d, float halfWidth) {  // |m + t d| ≤ halfWidth
  if (d == 0.0) return abs(m) <= halfWidth ? EVERYWHERE : NOWHERE;
  vec2 t = (vec2(-halfWidth, halfWidth) - m) / d;
  return vec2(min(t.x, t.y), max(t.x, t.y));
}

vec2 discInterval(vec3 m, vec3 d, float radius) {  // |m + t d|² ≤ r², solved as a t² + 2 b t + c ≤ 0
  float a = dot(d, d), b = dot(m, d), c = dot(m, m) - radius * radius;
  if (a == 0.0) return c <= 0.0 ? EVERYWHERE : NOWHERE;
  float discriminant = b * b - a * c;
  if (discriminant < 0.0) return NOWHERE;
  float s = sqrt(discriminant);
  return vec2(-b - s, -b + s) / a;
}

vec2 intersect(vec2 a, vec2 b) { return vec2(max(a.x, b.x), min(a.y, b.y)); }

// q ∈ [1e-3, 1]: where the link from `from` (a fluid cell centre, lattice coordinates) along `link` (−c_i)
// enters obstacle o's surface, as a fraction of the link. ½ for meshes (no analytic surface) and where the
// staircase of cell centres and the analytic shape disagree: a link that misses the surface, or starts
// inside the shape by more than rounding (an obstacle cut by a periodic face is not wrapped around it).
float wallFraction(Obstacle o, vec3 from, vec3 link) {
  uint shape = uint(o.centre.w);
  vec3 m = from - o.centre.xyz;
  vec2 t;
  if (shape == SHAPE_SPHERE) {
    t = discInterval(m, link, o.size.x);
  } else if (shape == SHAPE_CYLINDER) {  // the infinite cylinder around the axis, cut by the caps' slab
    vec3 axis = o.axis.xyz;
    t = intersect(discInterval(m - dot(m, axis) * axis, link - dot(link, axis) * axis, o.size.x),
                  slabInterval(dot(m, axis), dot(link, axis), o.axis.w));
  } else if (shape == SHAPE_BOX) {
    t = intersect(intersect(slabInterval(m.x, link.x, o.size.x), slabInterval(m.y, link.y, o.size.y)),
                  slabInterval(m.z, link.z, o.size.z));
  } else if (shape == SHAPE_CAPSULE) {  // convex: the hull of the cylinder's and the two caps' intervals
    vec3 axis = o.axis.xyz;
    vec2 parts[3] = vec2[](intersect(discInterval(m - dot(m, axis) * axis, link - dot(link, axis) * axis, o.size.x),
                                     slabInterval(dot(m, axis), dot(link, axis), o.axis.w)),
                           discInterval(m - o.axis.w * axis, link, o.size.x),
                           discInterval(m + o.axis.w * axis, link, o.size.x));
    t = NOWHERE;
    for (int k = 0; k < 3; ++k)
      if (parts[k].x <= parts[k].y) t = t.x <= t.y ? vec2(min(t.x, parts[k].x), max(t.y, parts[k].y)) : parts[k];
  } else {
    return 0.5;
  }
  if (t.x > t.y || t.x > 1.0 || t.y < 0.0 || t.x < -1e-4) return 0.5;
  return clamp(t.x, 1e-3, 1.0);
}

// The population f_i that reaches fluid cell p along C[i] from the wall of obstacle o in the cell
// source = p − C[i] (wrapped on periodic axes). `covered`: o covers the source cell now; a cell it
// uncovered this step still sends its wall's bounce-back, but where that wall now crosses the link is not
// known, so half-way. `rho`: the fluid cell's density a step ago.
float bounceBack(int i, ivec3 p, ivec3 source, bool covered, Obstacle o, float rho) {
  float toWall = loadKept(opposite(i), p);  // f*_ī(x_f)
  float momentum = 6.0 * W[i] * rho * dot(vec3(C[i]), o.velocity.xyz);
  if (!INTERPOLATED_BOUNCE_BACK || !covered) return toWall + momentum;
  // The fluid cell seen from the source's side of a periodic face, so that the link ends in the source.
  float q = wallFraction(o, vec3(source + C[i]) + 0.5, vec3(-C[i]));
  if (q > 0.5) return (toWall + (2.0 * q - 1.0) * awayFromWall(i, p) + momentum) / (2.0 * q);
  if (q == 0.5) return toWall + momentum;
  // q < ½ needs the next fluid cell away from the wall, x_f + c_i: half-way where there is none.
  ivec3 beyond = wrapPeriodic(p + C[i]);
  if (any(lessThan(beyond, ivec3(0))) || any(greaterThanEqual(beyond, SIZE))) return toWall + momentum;
  if (wallOf(flags[cellIndex(beyond, SIZE)]) != 0u) return toWall + momentum;
  float farther = loadKept(opposite(i), beyond);  // f*_ī(x_f + c_i)
  return 2.0 * q * toWall + (1.0 - 2.0 * q) * farther + momentum;
}

#endif
