#include "nn/naf_block_kernel.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "nn/nn_spec.h"
#include "nn/weight_packing.h"

namespace sixway::nn {
namespace {

// Pixels per invocation of the three image kernels. Blocks: measured fastest on lavapipe, each uniform weight
// read serves a row of pixels. Pixels: one each, for a GPU's threads (nn/kernel.h).
struct NafBlocks {
  int expand;            // along x, naf_norm_expand
  int dwPixels, dwRows;  // naf_dw_gate
  int tail;              // along x, naf_tail
};
NafBlocks nafBlocks(Tiling tiling) {
  return tiling == Tiling::Blocks ? NafBlocks{8, 4, 4, 8} : NafBlocks{1, 1, 1, 1};
}
constexpr uint32_t kAttentionThreads = 64;

const std::vector<float>& parameter(const ParameterMap& parameters, const std::string& key,
                                    const std::string& block) {
  const auto it = parameters.find(key);
  if (it == parameters.end()) throw gpu::GpuError(block + ": parameter '" + key + "' was not given");
  return it->second;
}

void append(std::vector<float>& to, const std::vector<float>& values) {
  to.insert(to.end(), values.begin(), values.end());
}

gpu::Buffer checkedUniform(const gpu::Context& context, const std::vector<float>& values,
                           const std::string& name) {
  if (values.size() * sizeof(float) > maxUniformBytes(context))
    throw gpu::GpuError(name +
                        ": the weights of one kernel exceed a uniform buffer; reduce the block's channels");
  return uniformBuffer(context, values, name);
}

// What the block's three image kernels share: 8 x 8 workgroups over the block's map.
gpu::SpecConstants mapSpec(const NafShape& shape) {
  gpu::SpecConstants constants;
  constants.set(spec::kLocalSizeX, kTile).set(spec::kLocalSizeY, kTile);
  constants.set(spec::kWidth, int(shape.width)).set(spec::kHeight, int(shape.height));
  return constants;
}

}  // namespace

std::array<double, 4> NafShape::kernelFlops() const {
  const double pixels = double(width) * height, c = channels, g = gated(), f = ffn();
  return {2.0 * pixels * c * 2 * g, 2.0 * pixels * 9 * 2 * g, 0.0,
          2.0 * pixels * (g * c + c * 2 * f + f * c + c * projection)};
}

double NafShape::flops() const {
  const std::array<double, 4> parts = kernelFlops();
  return parts[0] + parts[1] + parts[2] + parts[3];
}

NafBlockKernel::NafBlockKernel(const KernelSetup& setup, const NafShape& shape, const ParameterMap& p,
                               const std::string& name)
    : shape_(shape),
      expanded_(*setup.context, {shape.width, shape.height, uint32_t(gateLayout(2 * shape.gated()).padded)},
                setup.precision, name + " expanded"),
      gated_(*setup.context, {shape.width, shape.height, uint32_t(shape.gated())}, setup.precision,
             name + " gated") {
  const gpu::Context& context = *setup.context;
  auto get = [&](const char* key) -> const std::vector<float>& { return parameter(p, key, name); };
  const ChannelLayout channels = plainLayout(shape.channels), gated = plainLayout(shape.gated());
  const ChannelLayout expandedLayout = gateLayout(2 * shape.gated()), ffnLayout = gateLayout(2 * shape.ffn());

  std::vector<float> expand = packChannels(get("norm1.weight"), channels);
  append(expand, packChannels(get("norm1.bias"), channels));
  append(expand, packConvolution(get("conv1.weight"), &get("conv1.bias"), 1, expandedLayout, channels));
  normExpandWeights_ = checkedUniform(context, expand, name + " norm1+conv1");
  dwGateWeights_ = checkedUniform(
      context, packDepthwise(get("conv2.weight"), get("conv2.bias"), expandedLayout), name + " conv2");
  std::vector<float> attention = packConvolution(get("sca.weight"), &get("sca.bias"), 1, gated, gated);
  append(attention, packConvolution(get("conv3.weight"), nullptr, 1, channels, gated));
  attentionWeights_ = checkedUniform(context, attention, name + " sca+conv3");
  std::vector<float> tail = packChannels(get("conv3.bias"), channels);
  append(tail, packChannels(get("beta"), channels));
  append(tail, packChannels(get("norm2.weight"), channels));
  append(tail, packChannels(get("norm2.bias"), channels));
  append(tail, packConvolution(get("conv4.weight"), &get("conv4.bias"), 1, ffnLayout, channels));
  append(tail,
         packConvolution(get("conv5.weight"), &get("conv5.bias"), 1, channels, plainLayout(shape.ffn())));
  append(tail, packChannels(get("gamma"), channels));
  if (shape.projection)
    append(tail, packConvolution(get("projection.weight"), &get("projection.bias"), 1,
                                 plainLayout(shape.projection), channels));
  tailWeights_ = checkedUniform(context, tail, name + " norm2+conv4+conv5");

  const NafBlocks blocks = nafBlocks(setup.tiling);
  expandGrid_[0] = groupsFor(groupsFor(shape.width, blocks.expand), kTile);
  expandGrid_[1] = groupsFor(shape.height, kTile);
  dwGrid_[0] = groupsFor(groupsFor(shape.width, blocks.dwPixels), kTile);
  dwGrid_[1] = groupsFor(groupsFor(shape.height, blocks.dwRows), kTile);
  tailGrid_[0] = groupsFor(groupsFor(shape.width, blocks.tail), kTile);
  tailGrid_[1] = groupsFor(shape.height, kTile);
  const uint32_t partialCount = dwGrid_[0] * dwGrid_[1];
  partials_ =
      gpu::Buffer::storage(context, uint64_t(partialCount) * gated.padded * sizeof(float), name + " sums");
  scaledConv3_ = gpu::Buffer(context, uint64_t(channels.padded) * gated.padded * sizeof(float),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             gpu::MemoryKind::Device, name + " scaled conv3");
  if (scaledConv3_.size() > maxUniformBytes(context))
    throw gpu::GpuError(name + ": conv3 exceeds a uniform buffer; reduce the block's channels");

  using gpu::BindingType;
  const BindingType texels = BindingType::StorageTexelBuffer, storage = BindingType::StorageBuffer,
                    uniform = BindingType::UniformBuffer;
  gpu::ComputePipelineDesc desc;
  desc.shader = shaderName("naf_norm_expand", setup.precision);
  desc.bindings = {uniform, texels, storage};
  desc.spec = mapSpec(shape);
  desc.spec.set(spec::kChannels, shape.channels).set(spec::kGatedChannels, shape.gated());
  desc.spec.set(spec::kPx, blocks.expand).set(spec::kEps, shape.eps);
  normExpand_ = &setup.pipelines->get(desc);

  desc = {};
  desc.shader = shaderName("naf_dw_gate", setup.precision);
  desc.bindings = {uniform, texels, storage, storage};
  desc.spec = mapSpec(shape);
  desc.spec.set(spec::kGroups, gated.groups()).set(spec::kPx, blocks.dwPixels).set(spec::kPy, blocks.dwRows);
  dwGate_ = &setup.pipelines->get(desc);

  desc = {};
  desc.shader = "nn/naf_attention.comp";
  desc.bindings = {storage, uniform, storage};
  desc.spec.set(spec::kLocalSizeX, kAttentionThreads);
  desc.spec.set(spec::kGatedChannels, shape.gated()).set(spec::kChannels, shape.channels);
  desc.spec.set(spec::kPartialCount, int(partialCount))
      .set(spec::kPixels, float(shape.width) * float(shape.height));
  attention_ = &setup.pipelines->get(desc);

  desc = {};
  desc.shader = shaderName("naf_tail", setup.precision);
  desc.bindings = {uniform, uniform, texels, texels, storage};
  desc.spec = mapSpec(shape);
  desc.spec.set(spec::kChannels, shape.channels).set(spec::kGatedChannels, shape.gated());
  desc.spec.set(spec::kFfnChannels, shape.ffn()).set(spec::kProjectionChannels, shape.projection);
  desc.spec.set(spec::kPx, blocks.tail).set(spec::kEps, shape.eps);
  tail_ = &setup.pipelines->get(desc);
}

void NafBlockKernel::record(gpu::Sequence& sequence, const FeatureMap& input, const FeatureMap& output,
                            const std::string& timedAs) const {
  const std::span<const std::byte> none;
  auto stage = [&](const char* name, auto&& dispatch) {
    if (!timedAs.empty()) sequence.beginStage(timedAs + "/" + name);
    dispatch();
    if (!timedAs.empty()) sequence.endStage();
  };
  stage("norm_expand", [&] {
    sequence.dispatch(
        *normExpand_,
        {gpu::reads(normExpandWeights_), gpu::reads(input.texels()), gpu::writes(expanded_.buffer())}, none,
        expandGrid_[0], expandGrid_[1]);
  });
  stage("dw_gate", [&] {
    sequence.dispatch(*dwGate_,
                      {gpu::reads(dwGateWeights_), gpu::reads(expanded_.texels()),
                       gpu::writes(gated_.buffer()), gpu::writes(partials_)},
                      none, dwGrid_[0], dwGrid_[1]);
  });
  stage("attention", [&] {
    sequence.dispatch(*attention_,
                      {gpu::reads(partials_), gpu::reads(attentionWeights_), gpu::writes(scaledConv3_)}, none,
                      1);
  });
  stage("tail", [&] {
    sequence.dispatch(*tail_,
                      {gpu::reads(scaledConv3_), gpu::reads(tailWeights_), gpu::reads(gated_.texels()),
                       gpu::reads(input.texels()), gpu::writes(output.buffer())},
                      none, tailGrid_[0], tailGrid_[1]);
  });
}

}  // namespace sixway::nn
