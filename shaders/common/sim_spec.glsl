// Specialization constant ids of the simulation shaders (shaders/sim): one id per constant name across the
// family, so that the host sets a constant by the same id in every shader. src/sim/sim_spec.h holds the same
// ids; gpu::Pipeline and tests/gpu/test_spec_contract.cpp check that the two agree.
#ifndef SIXWAY_SIM_SPEC_GLSL
#define SIXWAY_SIM_SPEC_GLSL

#define SIM_SPEC_NX 0  // the lattice
#define SIM_SPEC_NY 1
#define SIM_SPEC_NZ 2
#define SIM_SPEC_SMOKE_UPRES 3
#define SIM_SPEC_FACE_XM 4  // boundary type per face
#define SIM_SPEC_FACE_XP 5
#define SIM_SPEC_FACE_YM 6
#define SIM_SPEC_FACE_YP 7
#define SIM_SPEC_FACE_ZM 8
#define SIM_SPEC_FACE_ZP 9
#define SIM_SPEC_PERIODIC_X 10
#define SIM_SPEC_PERIODIC_Y 11
#define SIM_SPEC_PERIODIC_Z 12
#define SIM_SPEC_INTERPOLATED_BOUNCE_BACK 13
#define SIM_SPEC_TAU0 14  // lbm_step.comp's fluid
#define SIM_SPEC_SMAGORINSKY 15
#define SIM_SPEC_BUOYANCY_T 16
#define SIM_SPEC_BUOYANCY_D 17
#define SIM_SPEC_UP_X 18
#define SIM_SPEC_UP_Y 19
#define SIM_SPEC_UP_Z 20
#define SIM_SPEC_BODY_X 21
#define SIM_SPEC_BODY_Y 22
#define SIM_SPEC_BODY_Z 23
#define SIM_SPEC_WIND_X 24
#define SIM_SPEC_WIND_Y 25
#define SIM_SPEC_WIND_Z 26
#define SIM_SPEC_PARABOLIC_INFLOW 27
#define SIM_SPEC_BOUNDARY_CELLS 28
#define SIM_SPEC_DECAY 29  // smoke_sources.comp
#define SIM_SPEC_PULL 31   // stream_bound.comp
#define SIM_SPEC_SPARSE 32  // the FCT passes: skip inactive bricks (sim_bricks.glsl)
#define SIM_SPEC_SPARSE_THRESHOLD 33  // smoke_activity.comp
#define SIM_SPEC_BOUNDARY_FACES 34      // lbm_step.comp's boundary pipelines
#define SIM_SPEC_BOUNDARY_OBSTACLES 35
#define SIM_SPEC_PARITY 36  // the in-place lattice's step (lbm_in_place.glsl)
#define SIM_SPEC_UNCOVERED_CELLS 37  // lbm_step.comp's last pipeline

#endif
