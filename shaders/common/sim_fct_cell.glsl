// The cell of an FCT pass's invocation (a workgroup is a brick, sim_bricks.glsl): in the sparse transport the
// brick is the workgroup's entry in the active list, in the dense one the workgroup's own. False past the list's
// end or the grid's. The including shader declares SPARSE, header[] and activeList[], and includes
// sim_bricks.glsl.
#ifndef SIXWAY_SIM_FCT_CELL_GLSL
#define SIXWAY_SIM_FCT_CELL_GLSL

bool fctCell(out ivec3 s) {
  ivec3 origin = ivec3(gl_WorkGroupID) * BRICK;
  if (SPARSE) {
    uint entry = brickListIndex();
    if (entry >= header[HEADER_ACTIVE_COUNT]) {
      s = ivec3(0);
      return false;
    }
    origin = brickOrigin(activeList[entry]);
  }
  s = origin + ivec3(gl_LocalInvocationID);
  return s.x < SMOKE.x && s.y < SMOKE.y && s.z < SMOKE.z;
}

#endif
