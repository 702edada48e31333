// The index of an invocation of a 1D kernel dispatched by gpu::Sequence::dispatchLinear: workgroups along x
// up to the device's limit, wrapping into y beyond it. Indices past the end exist; the kernel skips them.
// A macro, not a function: gl_WorkGroupSize takes the shader's local_size only after its layout declaration,
// which may come after this include.
#ifndef SIXWAY_LINEAR_INDEX_GLSL
#define SIXWAY_LINEAR_INDEX_GLSL

#define linearInvocationIndex() \
  (gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x)

#endif
