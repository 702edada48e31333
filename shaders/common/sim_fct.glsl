// Neighbour addressing shared by the FCT limiter and update passes (the including shader
// declares PERIODIC_X/Y/Z and includes sim_smoke.glsl).
#ifndef SIXWAY_SIM_FCT_GLSL
#define SIXWAY_SIM_FCT_GLSL

// Wraps n along axis a on a periodic axis; false when n lies outside the domain otherwise.
// Faces on the domain boundary carry no antidiffusive flux, so such neighbours are skipped.
bool wrapNeighbour(inout ivec3 n, int a) {
  if (n[a] >= 0 && n[a] < SMOKE[a]) return true;
  bool periodic = a == 0 ? PERIODIC_X : (a == 1 ? PERIODIC_Y : PERIODIC_Z);
  if (!periodic) return false;
  n[a] = (n[a] + SMOKE[a]) % SMOKE[a];
  return true;
}

#endif
