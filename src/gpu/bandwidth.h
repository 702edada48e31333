#pragma once
// The device's memory bandwidth as seen by a buffer-to-buffer copy: the reference against which
// memory-bound kernels (the lattice Boltzmann step) are judged (docs/conventions.md, "Metrics").
namespace sixway::gpu {

class Context;

// GB/s counting each copied byte twice (read and written): the median of several timed copies of a 64 MiB
// buffer after a warm-up copy, by vkCmdCopyBuffer and by a compute shader (shaders/gpu/copy_words.comp),
// whichever is faster (lavapipe's vkCmdCopyBuffer is a memcpy; NVIDIA's ran at a quarter of the shader's).
double measureCopyBandwidth(const Context& context);

}  // namespace sixway::gpu
