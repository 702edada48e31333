// Push constants of the fill_gradient test pipeline (both stages see the same block).
layout(push_constant) uniform Push {
  vec2 clipMin;     // rectangle corners in clip space, +y up
  vec2 clipMax;
  vec2 targetSize;  // pixels
  float alpha;      // the colour is premultiplied by it
} push;
