#include "nn/conv_matrix_kernel.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/safetensors.h"
#include "nn/nn_spec.h"
#include "nn/weight_packing.h"

namespace sixway::nn {
namespace {

// The shader's workgroup: 4 subgroups of 32, each owning MATRIX_M output pixels; and the K chunks it gathers
// between two barriers (conv2d_matrix.comp).
constexpr uint32_t kSubgroups = 4;
constexpr uint32_t kStageChunks = 4;
// Workgroups a dispatch should have at least, for a GPU of about a hundred multiprocessors to hold a few
// each: small maps split their output channels over several workgroups (each gathers the same inputs).
constexpr uint32_t kMinWorkgroups = 256;

uint32_t roundUp(uint32_t value, uint32_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

gpu::Buffer storageBuffer(const gpu::Context& context, std::span<const std::byte> bytes, std::string name) {
  gpu::Buffer buffer(context, bytes.size(),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     gpu::MemoryKind::Device, std::move(name));
  buffer.upload(bytes);
  return buffer;
}

}  // namespace

ConvMatrixKernel::ConvMatrixKernel(const KernelSetup& setup, const ConvShape& shape,
                                   const std::vector<float>& weight, const std::vector<float>& bias,
                                   const std::string& name)
    : shape_(shape) {
  const gpu::Context& context = *setup.context;
  const gpu::MatrixShape matrix = context.capabilities().cooperativeMatrix;
  if (!matrix) throw gpu::GpuError(name + ": the device has no cooperative matrices sixway can use");
  if (setup.precision != Precision::Fp16)
    throw gpu::GpuError(name + ": the cooperative-matrix conv2d takes fp16 maps only");
  if (shape.transposed || shape.inputChannels.empty() || shape.inputChannels.size() > 2)
    throw gpu::GpuError(name + ": the cooperative-matrix conv2d takes a conv2d of one or two inputs");
  if (bias.size() != size_t(shape.outChannels))
    throw gpu::GpuError(name + ": " + std::to_string(bias.size()) + " biases for " +
                        std::to_string(shape.outChannels) + " output channels");

  const int taps = shape.kernel * shape.kernel;
  const ChannelLayout in = concatLayout(shape.inputChannels);
  const uint32_t kChunks = (uint32_t(taps * in.padded) + matrix.k - 1) / matrix.k;
  const uint32_t nPadded = roundUp(uint32_t(shape.outChannels), matrix.n);
  const std::vector<float> packed =
      packMatrix(weight, taps, shape.outChannels, in, size_t(kChunks) * matrix.k, nPadded);
  const io::Tensor half = io::Tensor::fromFloat("", io::DType::F16, {int64_t(packed.size())}, packed);
  weights_ = storageBuffer(context, std::as_bytes(std::span(half.bytes)), name + " matrix weights");
  std::vector<float> paddedBias(nPadded, 0.0f);
  std::copy(bias.begin(), bias.end(), paddedBias.begin());
  bias_ = storageBuffer(context, std::as_bytes(std::span(paddedBias)), name + " bias");

  // Output channel tiles per workgroup: all of them, unless the map is too small to fill kMinWorkgroups
  // workgroups or the products would not fit in shared memory; then the fewest per workgroup that divide
  // them.
  const MapShape o = shape.output();
  const uint32_t tilePixels = kSubgroups * matrix.m, nTiles = nPadded / matrix.n;
  gridX_ = groupsFor(o.width * o.height, tilePixels);
  const auto sharedBytes = [&](uint32_t tiles) {
    return tilePixels * (kStageChunks * matrix.k + 8) * 2 + tilePixels * tiles * matrix.n * 4;
  };
  const uint32_t sharedLimit = context.limits().maxComputeSharedMemorySize;
  uint32_t tiles = 0;
  for (uint32_t split = 1; split <= nTiles; ++split) {
    if (nTiles % split || sharedBytes(nTiles / split) > sharedLimit) continue;
    tiles = nTiles / split;
    gridY_ = split;
    if (gridX_ * split >= kMinWorkgroups) break;
  }
  if (!tiles)
    throw gpu::GpuError(name + ": one output channel tile needs more shared memory than the device has");

  const int groupsA = concatLayout({shape.inputChannels[0]}).groups();
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("conv2d_matrix", Precision::Fp16);
  desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageTexelBuffer,
                   gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                   gpu::BindingType::StorageBuffer};
  desc.spec.set(spec::kKernel, shape.kernel).set(spec::kStride, shape.stride);
  desc.spec.set(spec::kInWidth, int(shape.inWidth)).set(spec::kInHeight, int(shape.inHeight));
  desc.spec.set(spec::kOutWidth, int(o.width)).set(spec::kOutHeight, int(o.height));
  desc.spec.set(spec::kGroupsA, groupsA).set(spec::kGroupsB, in.groups() - groupsA);
  desc.spec.set(spec::kActivation, int(shape.activation)).set(spec::kNegativeSlope, shape.negativeSlope);
  desc.spec.set(spec::kMatrixM, int(matrix.m))
      .set(spec::kMatrixN, int(matrix.n))
      .set(spec::kMatrixK, int(matrix.k));
  desc.spec.set(spec::kNTiles, int(tiles))
      .set(spec::kKChunks, int(kChunks))
      .set(spec::kNPadded, int(nPadded));
  desc.spec.set(spec::kOutGroups, int(o.groups()));
  pipeline_ = &setup.pipelines->get(desc);
}

void ConvMatrixKernel::record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& inputs,
                              const FeatureMap& output) const {
  if (inputs.size() != shape_.inputChannels.size())
    throw gpu::GpuError("conv matrix kernel: " + std::to_string(inputs.size()) + " inputs for a layer of " +
                        std::to_string(shape_.inputChannels.size()));
  sequence.dispatch(*pipeline_,
                    {gpu::reads(inputs[0]->texels()), gpu::reads(inputs.back()->texels()),
                     gpu::reads(weights_), gpu::reads(bias_), gpu::writes(output.buffer())},
                    std::span<const std::byte>(), gridX_, gridY_);
}

}  // namespace sixway::nn
