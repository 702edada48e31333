#include "nn/conv_kernel.h"

#include <algorithm>
#include <numeric>

#include "gpu/check.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "nn/nn_spec.h"
#include "nn/weight_packing.h"

namespace sixway::nn {
namespace {

// Output pixels along x per invocation (see the shaders), and input groups per unrolled slice of conv2d.
constexpr int kConvPixels = 4;
constexpr int kSliceGroups = 2;
constexpr int kTransposedPixels = 8;

struct Push {
  int32_t firstGroup;  // the output group of the chunk's first
};

struct Block {
  int pixels, rows;  // output pixels along x and rows per invocation
};

// The conv2d block. Blocks: 4 x 8 (fastest on lavapipe), fewer rows, then fewer pixels, while an output group
// would not fill one workgroup: lavapipe runs every lane of a workgroup, so on the small maps of a UNet's
// deep levels (8 x 8) a 4 x 1 block left three lanes of four idle. Pixels: rows, then pixels, halve until the
// dispatch has kGpuInvocations invocations (or one pixel each).
Block convBlock(const MapShape& out, int outGroups, Tiling tiling) {
  Block b{kConvPixels, 8};
  const auto blocks = [&] {
    return uint64_t(groupsFor(out.width, b.pixels)) * groupsFor(out.height, b.rows);
  };
  if (tiling == Tiling::Blocks) {
    while (b.rows > 1 && blocks() < kTile * kTile) b.rows /= 2;
    while (b.pixels > 1 && blocks() < kTile * kTile) b.pixels /= 2;
    return b;
  }
  while ((b.rows > 1 || b.pixels > 1) && blocks() * outGroups < kGpuInvocations) {
    if (b.rows > 1)
      b.rows /= 2;
    else
      b.pixels /= 2;
  }
  return b;
}

// Input pixels along x per conv_transpose2x2 invocation: 8, halved as conv2d's blocks are (Blocks: while an
// output group would not fill one workgroup; Pixels: until the dispatch has kGpuInvocations invocations).
int transposedPixels(const ConvShape& shape, int outGroups, Tiling tiling) {
  int pixels = kTransposedPixels;
  const auto tooFew = [&] {
    const uint64_t invocations = uint64_t(groupsFor(shape.inWidth, pixels)) * shape.inHeight;
    return tiling == Tiling::Blocks ? invocations < kTile * kTile : invocations * outGroups < kGpuInvocations;
  };
  while (pixels > 1 && tooFew()) pixels /= 2;
  return pixels;
}

}  // namespace

int ConvShape::inChannels() const {
  return std::accumulate(inputChannels.begin(), inputChannels.end(), 0);
}

MapShape ConvShape::output() const {
  if (transposed) return {inWidth * 2, inHeight * 2, uint32_t(outChannels)};
  // PyTorch: floor((n + 2 * (k / 2) - k) / stride) + 1.
  auto size = [this](uint32_t n) { return (n + 2 * (kernel / 2) - kernel) / stride + 1; };
  return {size(inWidth), size(inHeight), uint32_t(outChannels)};
}

double ConvShape::flops() const {
  const MapShape out = output();
  const double taps = transposed ? 1.0 : double(kernel) * kernel;  // a transposed 2x2 output pixel sees 1 tap
  return 2.0 * inChannels() * outChannels * taps * out.width * out.height;
}

ConvKernel::ConvKernel(const KernelSetup& setup, const ConvShape& shape, const std::vector<float>& weight,
                       const std::vector<float>& bias, const std::string& name)
    : shape_(shape) {
  const int taps = shape.transposed ? 4 : shape.kernel * shape.kernel;
  const ChannelLayout in = concatLayout(shape.inputChannels), out = plainLayout(shape.outChannels);
  const std::vector<float> packed = packConvolution(
      shape.transposed ? swapInOut(weight, shape.inChannels(), shape.outChannels, taps) : weight, &bias, taps,
      out, in);
  outGroups_ = out.groups();
  const size_t groupFloats = packed.size() / outGroups_;
  const uint32_t limit = maxUniformBytes(*setup.context);
  groupsPerChunk_ = std::min<int>(outGroups_, int(limit / (groupFloats * sizeof(float))));
  if (groupsPerChunk_ < 1)
    throw gpu::GpuError(name + ": " + std::to_string(shape.inChannels()) +
                        " input channels need more weights per output group than a " + std::to_string(limit) +
                        "-byte uniform buffer holds; reduce the layer's input channels");
  for (int first = 0; first < outGroups_; first += groupsPerChunk_) {
    std::vector<float> chunk(groupFloats * groupsPerChunk_, 0.0f);  // the last chunk is padded with zeros
    const size_t count = groupFloats * std::min(groupsPerChunk_, outGroups_ - first);
    std::copy_n(packed.begin() + groupFloats * first, count, chunk.begin());
    chunks_.push_back(
        uniformBuffer(*setup.context, chunk, name + " weights " + std::to_string(chunks_.size())));
  }

  const MapShape o = shape.output();
  Block block = convBlock(o, outGroups_, setup.tiling);
  if (shape.rows) block.rows = shape.rows;
  int pixels = shape.transposed ? transposedPixels(shape, outGroups_, setup.tiling) : block.pixels;
  if (shape.pixels) pixels = shape.pixels;
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName(shape.transposed ? "conv_transpose2x2" : "conv2d", setup.precision);
  desc.pushConstantBytes = sizeof(Push);
  const int weightVec4s = int(groupFloats / 4) * groupsPerChunk_;
  desc.spec.set(spec::kLocalSizeX, kTile).set(spec::kLocalSizeY, kTile);
  desc.spec.set(spec::kInWidth, int(shape.inWidth)).set(spec::kInHeight, int(shape.inHeight));
  desc.spec.set(spec::kPx, pixels).set(spec::kWeightVec4s, weightVec4s);
  desc.spec.set(spec::kActivation, int(shape.activation)).set(spec::kNegativeSlope, shape.negativeSlope);
  if (shape.transposed) {
    desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::UniformBuffer,
                     gpu::BindingType::StorageBuffer};
    desc.spec.set(spec::kGroupsIn, in.groups());
    gridX_ = groupsFor(groupsFor(shape.inWidth, pixels), kTile);
    gridY_ = groupsFor(shape.inHeight, kTile);
  } else {
    const int rows = block.rows;
    const int groupsA = concatLayout({shape.inputChannels[0]}).groups();
    desc.bindings = {gpu::BindingType::StorageTexelBuffer, gpu::BindingType::StorageTexelBuffer,
                     gpu::BindingType::UniformBuffer, gpu::BindingType::StorageBuffer};
    desc.spec.set(spec::kKernel, shape.kernel).set(spec::kStride, shape.stride);
    desc.spec.set(spec::kOutWidth, int(o.width)).set(spec::kOutHeight, int(o.height));
    desc.spec.set(spec::kGroupsA, groupsA).set(spec::kGroupsB, in.groups() - groupsA);
    desc.spec.set(spec::kPy, rows).set(spec::kSlice, kSliceGroups);
    gridX_ = groupsFor(groupsFor(o.width, pixels), kTile);
    gridY_ = groupsFor(groupsFor(o.height, rows), kTile);
  }
  pipeline_ = &setup.pipelines->get(desc);
}

void ConvKernel::record(gpu::Sequence& sequence, const std::vector<const FeatureMap*>& inputs,
                        const FeatureMap& output) const {
  if (inputs.size() != shape_.inputChannels.size() || (shape_.transposed && inputs.size() != 1) ||
      inputs.size() > 2)
    throw gpu::GpuError("conv kernel: " + std::to_string(inputs.size()) + " inputs for a layer of " +
                        std::to_string(shape_.inputChannels.size()));
  for (int chunk = 0; chunk < int(chunks_.size()); ++chunk) {
    const int first = chunk * groupsPerChunk_, count = std::min(groupsPerChunk_, outGroups_ - first);
    std::vector<gpu::Binding> bindings;
    if (shape_.transposed)
      bindings = {gpu::reads(inputs[0]->texels()), gpu::reads(chunks_[chunk]), gpu::writes(output.buffer())};
    else
      bindings = {gpu::reads(inputs[0]->texels()), gpu::reads(inputs.back()->texels()),
                  gpu::reads(chunks_[chunk]), gpu::writes(output.buffer())};
    sequence.dispatch(*pipeline_, bindings, Push{first}, gridX_, gridY_, uint32_t(count));
  }
}

}  // namespace sixway::nn
