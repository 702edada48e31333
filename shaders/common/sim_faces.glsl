// The boundary type of each domain face. The including shader declares the specialization
// constants FACE_XM, FACE_XP, FACE_YM, FACE_YP, FACE_ZM, FACE_ZP (types from sim_grid.glsl).
#ifndef SIXWAY_SIM_FACES_GLSL
#define SIXWAY_SIM_FACES_GLSL

// 0..5 = x−, x+, y−, y+, z−, z+. A chain of ?:, not a switch: the validation layer of SDK 1.3.239
// reports a switch over specialization constants as invalid SPIR-V after specialization.
uint faceType(int face) {
  return face == 0 ? FACE_XM
       : face == 1 ? FACE_XP
       : face == 2 ? FACE_YM
       : face == 3 ? FACE_YP
       : face == 4 ? FACE_ZM
                   : FACE_ZP;
}

#endif
