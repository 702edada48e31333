# The smoke simulation (src/sim): lattice Boltzmann flow, obstacles, smoke transport.
list(APPEND SIXWAY_SHADERS
  sim/obstacles.comp
  sim/voxelize_mesh.comp
  sim/lbm_init.comp
  sim/lbm_step.comp
  sim/forces.comp
  sim/smoke_sources.comp
  sim/fct_fluxes.comp
  sim/fct_limiter.comp
  sim/fct_update.comp
  sim/smoke_export.comp
  sim/stream_bound.comp
)
