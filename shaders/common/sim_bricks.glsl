// The sparse smoke transport (docs/simulation.md, "Sparse smoke"): the smoke grid in bricks of 16×2×2 cells, one
// workgroup of the FCT passes each. A brick is active when a value of one of its cells or of the cells around it
// (one cell wide: the FCT's stencil) exceeds the threshold. smoke_activity.comp lists the active bricks and those
// that just turned inactive; the FCT passes run on the first list only (an indirect dispatch, so that a skipped
// brick costs nothing, as it would not if a workgroup returned early: llvmpipe runs both sides of a branch under
// a mask), and smoke_clear.comp zeroes the second. The including shader includes sim_smoke.glsl first.
#ifndef SIXWAY_SIM_BRICKS_GLSL
#define SIXWAY_SIM_BRICKS_GLSL

// 16 cells along x keep a brick's rows two cache lines long (vec2 per cell); src/sim/smoke_transport.cpp agrees.
const int BRICK_X = 16, BRICK_Y = 2, BRICK_Z = 2;
const ivec3 BRICK = ivec3(BRICK_X, BRICK_Y, BRICK_Z);
// Scalar expressions: the validation layer of SDK 1.3.239 rejects some vector specialization-constant
// expressions after specialization although spirv-val accepts them (as in fct_fluxes.comp).
const ivec3 BRICKS = ivec3((NX * SMOKE_UPRES + BRICK_X - 1) / BRICK_X, (NY * SMOKE_UPRES + BRICK_Y - 1) / BRICK_Y,
                           (NZ * SMOKE_UPRES + BRICK_Z - 1) / BRICK_Z);
const uint BRICK_COUNT = uint(BRICKS.x * BRICKS.y * BRICKS.z);

// The brick header, words: the active bricks' dispatch (x, y, z), the cleared bricks' dispatch, then the two
// list lengths. The host zeroes it before each activity pass. A list's workgroups run in rows of
// BRICK_LIST_ROW (Vulkan guarantees 65535 workgroups along x; 128×256×128 smoke cells are 65536 bricks).
const uint HEADER_ACTIVE_DISPATCH = 0u;
const uint HEADER_CLEAR_DISPATCH = 3u;
const uint HEADER_ACTIVE_COUNT = 6u;
const uint HEADER_CLEAR_COUNT = 7u;
const uint BRICK_LIST_ROW = 32768u;

// Activity bits per brick (smoke_activity.comp's memory of the last substep).
const uint BRICK_ACTIVE = 1u;

// The position of this workgroup in a list dispatched by brickListDispatch.
uint brickListIndex() { return gl_WorkGroupID.x + gl_WorkGroupID.y * BRICK_LIST_ROW; }

// The first cell of a brick.
ivec3 brickOrigin(uint brick) { return cellOf(brick, BRICKS) * BRICK; }

#endif
