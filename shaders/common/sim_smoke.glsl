// The smoke grid: SMOKE_UPRES times finer than the lattice on each axis, values (density,
// temperature) per cell. The including shader declares NX, NY, NZ (the lattice) and SMOKE_UPRES.
#ifndef SIXWAY_SIM_SMOKE_GLSL
#define SIXWAY_SIM_SMOKE_GLSL

const ivec3 LATTICE = ivec3(NX, NY, NZ);
const ivec3 SMOKE = LATTICE * SMOKE_UPRES;
const uint SMOKE_CELLS = uint(SMOKE.x * SMOKE.y * SMOKE.z);

ivec3 latticeCellOf(ivec3 smokeCell) { return smokeCell / SMOKE_UPRES; }

#endif
