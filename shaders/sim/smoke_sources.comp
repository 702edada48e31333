#version 460
// Smoke sources and dissipation, once per lattice step: cells inside an active inlet take the
// inlet's density and temperature (or gain them: an emitter's rates); elsewhere both decay by the dissipation factor. The sparse transport
// (sim_bricks.glsl) decays its active bricks in smoke_decay.comp, the only ones holding smoke, and runs this over
// the box of the inlets' cells (the push constants) only to set them.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;
layout(constant_id = SIM_SPEC_DECAY) const float DECAY = 1.0;  // exp(−dissipation · dt) per lattice step
layout(constant_id = SIM_SPEC_SPARSE) const bool SPARSE = false;

#include "linear_index.glsl"
#include "sim_grid.glsl"
#include "sim_smoke.glsl"

layout(std430, binding = 0) readonly buffer Params { StepParams params[]; };
layout(std430, binding = 1) readonly buffer Flags { uint flags[]; };
layout(std430, binding = 2) buffer Smoke { vec2 smoke[]; };
layout(push_constant) uniform Push {
  uint step;
  uint unused[3];
  ivec4 boxMin;   // sparse: xyz the first smoke cell of the inlets' box
  ivec4 boxSize;  // sparse: xyz its cells per axis
} push;

void main() {
  uint index = linearInvocationIndex();
  if (SPARSE && index >= uint(push.boxSize.x * push.boxSize.y * push.boxSize.z)) return;
  if (!SPARSE && index >= SMOKE_CELLS) return;
  ivec3 s = SPARSE ? push.boxMin.xyz + cellOf(index, push.boxSize.xyz) : cellOf(index, SMOKE);
  uint cell = cellIndex(s, SMOKE);
  uint inlet = inletOf(flags[cellIndex(latticeCellOf(s), LATTICE)]);
  if (inlet != 0u) {
    vec4 source = params[push.step].inlets[inlet - 1u].smoke;
    smoke[cell] = (uint(source.w) & INLET_ADDS) != 0u ? smoke[cell] + source.xy : source.xy;
  }
  else if (!SPARSE && DECAY != 1.0) smoke[cell] *= DECAY;
}
