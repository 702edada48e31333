// The simulation grid: cell indexing (x fastest), cell flags, boundary face types, and the
// obstacle/inlet tables shared by the sim shaders. Mirrored by src/sim/sim_params.h (std430).
#ifndef SIXWAY_SIM_GRID_GLSL
#define SIXWAY_SIM_GRID_GLSL

// Boundary face types (io::BoundaryType order).
const uint FACE_NO_SLIP = 0u;
const uint FACE_FREE_SLIP = 1u;
const uint FACE_OUTFLOW = 2u;
const uint FACE_PERIODIC = 3u;
const uint FACE_INFLOW = 4u;

// Cell flags: bits 0..7 the obstacle covering the cell, plus one (0: fluid); bits 8..15 the same
// for the previous step; bits 16..23 the inlet forcing the cell, plus one (0: none).
const uint FLAG_OBSTACLE_MASK = 0xffu;
const uint FLAG_PREVIOUS_SHIFT = 8u;
const uint FLAG_INLET_SHIFT = 16u;
const uint FLAG_INLET_MASK = 0xff0000u;

uint obstacleOf(uint flags) { return flags & FLAG_OBSTACLE_MASK; }
bool isSolid(uint flags) { return (flags & FLAG_OBSTACLE_MASK) != 0u; }
uint previousObstacleOf(uint flags) { return (flags >> FLAG_PREVIOUS_SHIFT) & FLAG_OBSTACLE_MASK; }
uint inletOf(uint flags) { return (flags & FLAG_INLET_MASK) >> FLAG_INLET_SHIFT; }
// The obstacle a population streaming out of this cell comes from: the one covering it now, or,
// for a cell a moving obstacle has just uncovered, the one that covered it a step ago (its own
// populations are not valid yet: it starts from equilibrium in this step). 0: a fluid cell.
uint wallOf(uint flags) {
  uint now = obstacleOf(flags);
  return now != 0u ? now : previousObstacleOf(flags);
}

uint cellIndex(ivec3 p, ivec3 size) { return uint(p.x + size.x * (p.y + size.y * p.z)); }
ivec3 cellOf(uint index, ivec3 size) {
  return ivec3(int(index) % size.x, (int(index) / size.x) % size.y, int(index) / (size.x * size.y));
}

const uint MAX_OBSTACLES = 16u;
const uint MAX_INLETS = 8u;

const uint SHAPE_SPHERE = 0u;
const uint SHAPE_CYLINDER = 1u;
const uint SHAPE_BOX = 2u;
const uint SHAPE_MESH = 3u;
const uint SHAPE_CAPSULE = 4u;

// An obstacle at one step, in lattice coordinates (cell centres at integer + 0.5).
struct Obstacle {
  vec4 centre;       // xyz: centre (mesh: translation); w: shape
  vec4 velocity;     // xyz: cells per step (rigid translation)
  vec4 axis;         // cylinder, capsule: xyz axis, w: half height (capsule: of its segment)
  vec4 size;         // box: half sizes; sphere/cylinder/capsule: x = radius
  vec4 rotation[3];  // mesh: rows of the world→object rotation divided by the scale
  vec4 meshOrigin;   // mesh: object-space corner of its occupancy grid; w: its cell size
  ivec4 meshGrid;    // mesh: occupancy grid size xyz, w: first word in the occupancy buffer
};

struct Inlet {
  vec4 centre;    // disk and ball: centre; box: minimum corner; w: shape (INLET_*)
  vec4 normal;    // disk: unit normal, w: radius; ball: w: radius; box: maximum corner
  vec4 velocity;  // cells per step; w: noise amplitude (fraction of the speed)
  vec4 smoke;     // x: density, y: temperature (or per step: INLET_ADDS), z: 1 when active this step, w: INLET_*
};

const float INLET_DISK = 0.0, INLET_BOX = 1.0, INLET_BALL = 2.0;
// Inlet.smoke.w bits: the cells gain smoke.xy each step (else they hold it); the flow there is set to the
// inlet's velocity (else left to the fluid).
const uint INLET_ADDS = 1u, INLET_SETS_FLOW = 2u;
bool inletSetsFlow(Inlet inlet) { return (uint(inlet.smoke.w) & INLET_SETS_FLOW) != 0u; }

// Everything that changes from step to step, written by the host before each submission.
struct StepParams {
  Obstacle obstacles[MAX_OBSTACLES];
  Inlet inlets[MAX_INLETS];
  uvec4 counts;     // x: obstacles, y: inlets, z: step number (for noise), w: unused
  ivec4 solidMin;   // cells that are or were solid this step or the last, grown by one cell:
  ivec4 solidMax;   // outside [solidMin, solidMax] no cell or neighbour is solid (max exclusive)
};

bool nearSolid(StepParams p, ivec3 cell) {
  return all(greaterThanEqual(cell, p.solidMin.xyz)) && all(lessThan(cell, p.solidMax.xyz));
}

bool insideInlet(Inlet inlet, vec3 p) {
  if (inlet.centre.w == INLET_BALL) {
    vec3 d = p - inlet.centre.xyz;
    return dot(d, d) <= inlet.normal.w * inlet.normal.w;
  }
  if (inlet.centre.w == INLET_DISK) {  // disk: one cell thick on the side its normal points to
    vec3 d = p - inlet.centre.xyz;
    float along = dot(d, inlet.normal.xyz);
    float across = length(d - along * inlet.normal.xyz);
    return along >= -0.5 && along < 0.5 && across <= inlet.normal.w;
  }
  return all(greaterThanEqual(p, inlet.centre.xyz)) && all(lessThan(p, inlet.normal.xyz));
}

// Integer hash (Jarzynski & Olano 2020, pcg3d), for reproducible inflow noise.
uvec3 pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

vec3 noise3(ivec3 cell, uint step) {
  return vec3(pcg3d(uvec3(cell) ^ uvec3(step * 747796405u))) * (2.0 / 4294967295.0) - 1.0;
}

#endif
