#version 460
// The smoke grid as the renderers read it (src/render/volume.h): the interleaved (density, temperature)
// pairs of the transport split into two float grids, on the GPU so that a frame never visits the host.
#extension GL_GOOGLE_include_directive : require
#include "sim_spec.glsl"

layout(local_size_x = 64) in;
layout(constant_id = SIM_SPEC_NX) const int NX = 1;
layout(constant_id = SIM_SPEC_NY) const int NY = 1;
layout(constant_id = SIM_SPEC_NZ) const int NZ = 1;
layout(constant_id = SIM_SPEC_SMOKE_UPRES) const int SMOKE_UPRES = 1;

#include "linear_index.glsl"
#include "sim_grid.glsl"
#include "sim_smoke.glsl"

layout(std430, binding = 0) readonly buffer Smoke { vec2 smoke[]; };
layout(std430, binding = 1) writeonly buffer Density { float density[]; };
layout(std430, binding = 2) writeonly buffer Temperature { float temperature[]; };

void main() {
  uint index = linearInvocationIndex();
  if (index >= SMOKE_CELLS) return;
  vec2 q = smoke[index];
  density[index] = q.x;
  temperature[index] = q.y;
}
