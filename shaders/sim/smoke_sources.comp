#version 460
// Smoke sources and dissipation, once per lattice step: cells inside an active inlet take the
// inlet's density and temperature; elsewhere both decay by the dissipation factor.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_DECAY) const float DECAY = 1.0;  // exp(−dissipation · dt) per lattice step

#include "linear_index.glsl"
#include "sim_grid.glsl"
#include "sim_smoke.glsl"

layout(std430, binding = 0) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 2) buffer Smoke { vec2 smoke[]; };
layout(push_constant) uniform Push { uint step; } push;

void main() {
  uint index = linearInvocationIndex();
  if (index >= SMOKE_CELLS) return;
  uint flag = flags[cellIndex(latticeCellOf(cellOf(index, SMOKE)), LATTICE)];
  uint inlet = inletOf(flag);
  if (inlet != 0u) smoke[index] = params[push.step].inlets[inlet - 1u].smoke.xy;
  else if (DECAY != 1.0) smoke[index] *= DECAY;
}
