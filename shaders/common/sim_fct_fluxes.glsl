// The antidiffusive fluxes of the FCT passes: one buffer per axis, element s the flux through smoke cell s's
// lower face along that axis (+ along the axis). Three buffers, not one [cell][axis] array, so that no buffer
// outgrows the storage-buffer range before the lattice's own buffers do (128 MiB on lavapipe: 8 bytes a cell
// each, instead of 24). The including shader declares the buffers antidiffusiveX/Y/Z.
#ifndef SIXWAY_SIM_FCT_FLUXES_GLSL
#define SIXWAY_SIM_FCT_FLUXES_GLSL

#define SIXWAY_FCT_FLUX(a, s) \
  ((a) == 0 ? antidiffusiveX[s] : (a) == 1 ? antidiffusiveY[s] : antidiffusiveZ[s])

#endif
