# The smoke simulation (src/sim): lattice Boltzmann flow, obstacles, smoke transport. The shaders that touch the
# populations in the simulation also come as an LBM_FP16 variant (16-bit population storage, lbm_lattice.glsl).
list(APPEND SIXWAY_SHADERS
  sim/obstacles.comp
  sim/voxelize_mesh.comp
  sim/lbm_init.comp
  sim/lbm_step.comp
  sim/lbm_keep_away.comp
  sim/forces.comp
  sim/smoke_sources.comp
  sim/smoke_activity.comp
  sim/smoke_clear.comp
  sim/smoke_decay.comp
  sim/fct_fluxes.comp
  sim/fct_limiter.comp
  sim/fct_update.comp
  sim/smoke_export.comp
  sim/stream_bound.comp
  sim/lbm_init.comp:LBM_FP16
  sim/lbm_step.comp:LBM_FP16
  sim/lbm_keep_away.comp:LBM_FP16
  sim/forces.comp:LBM_FP16
)
