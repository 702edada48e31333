#pragma once
// What every layer kernel of the network shares: the device, the pipeline cache, the storage precision of
// the feature maps, and how output channel groups are dispatched.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "nn/feature_map.h"

namespace sixway::gpu {
class Context;
class Pipeline;
class PipelineCache;
struct ComputePipelineDesc;
}  // namespace sixway::gpu

namespace sixway::nn {

// Pipelines shared by every kernel with the same shader, bindings and specialization (a network's four
// adapters use one set): each is created, and compiled by the driver, once.
class PipelinePool {
 public:
  PipelinePool(const gpu::Context& context, const gpu::PipelineCache& cache);
  ~PipelinePool();
  const gpu::Pipeline& get(const gpu::ComputePipelineDesc& desc);
  size_t size() const { return pipelines_.size(); }

 private:
  const gpu::Context* context_;
  const gpu::PipelineCache* cache_;
  std::map<std::string, std::unique_ptr<gpu::Pipeline>> pipelines_;  // by shader, bindings and constants
};

// How much of a map one invocation computes. Blocks: several output pixels (and every channel in the NAF
// kernels), so that each weight or texel load serves many outputs; fastest on lavapipe, whose few threads are
// filled anyway. Pixels: conv blocks shrink until a dispatch has kGpuInvocations invocations (down to one
// pixel) and the NAF kernels take one pixel each, since a GPU's tens of thousands of threads idle otherwise
// (NVIDIA's H200 ran the 64x64 middle of the UNet at the same speed at 256² and 512² maps: too few
// invocations). Matrix: as Pixels, but the conv2d layers of fp16 maps run on cooperative matrices (tensor
// cores: conv_matrix_kernel.h); only where the device has them (gpu/cooperative_matrix.h). Device: Blocks on
// a CPU device, else Matrix where the device has cooperative matrices, else Pixels.
enum class Tiling { Device, Blocks, Pixels, Matrix };
// Throws gpu::GpuError when Matrix is asked of a device without cooperative matrices.
Tiling resolveTiling(Tiling requested, const gpu::Context& context);
const char* tilingName(Tiling tiling);
constexpr uint64_t kGpuInvocations = uint64_t(1) << 16;

struct KernelSetup {
  const gpu::Context* context;
  PipelinePool* pipelines;
  Precision precision = Precision::Fp32;
  Tiling tiling = Tiling::Blocks;  // resolved: Blocks, Pixels or Matrix
};

// "nn/<name>.comp", or its NN_FP16 variant.
std::string shaderName(const char* name, Precision precision);

// Workgroups of 8 x 8 invocations for every image kernel.
constexpr uint32_t kTile = 8;
constexpr uint32_t groupsFor(uint32_t items, uint32_t perGroup) {
  return (items + perGroup - 1) / perGroup;
}

// A device-local uniform buffer holding `values` (vec4 data, so a multiple of 4 floats).
gpu::Buffer uniformBuffer(const gpu::Context& context, const std::vector<float>& values, std::string name);

// The largest uniform buffer the kernels bind: the device's limit, at most 64 KiB.
uint32_t maxUniformBytes(const gpu::Context& context);

}  // namespace sixway::nn
