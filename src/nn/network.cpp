#include "nn/network.h"

#include <algorithm>
#include <optional>
#include <variant>

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "nn/conv_kernel.h"
#include "nn/conv_matrix_kernel.h"
#include "nn/io_kernels.h"
#include "nn/naf_block_kernel.h"
#include "nn/upsample_kernel.h"

namespace sixway::nn {

struct Network::Layer {
  const Node* node;
  // std::monostate: a projection fused into the NAFBlock before it, which computes it.
  std::variant<std::monostate, InputKernel, ConvKernel, ConvMatrixKernel, UpsampleKernel, NafBlockKernel,
               OutputKernel>
      kernel;
  std::optional<FeatureMap> output;  // what the kernel writes (none for the output node and fused layers)
  std::vector<int> inputs;           // the input nodes
  double flops = 0.0;
};

namespace {

std::vector<float> tensorValues(const io::SafetensorsFile& file, const std::string& name) {
  return file.at(name).toFloat();
}

ParameterMap nafParameters(const io::SafetensorsFile& file, const Node& node) {
  ParameterMap parameters;
  for (const TensorRequirement& t : requiredTensors(node))
    parameters[t.name.substr(node.name.size() + 1)] = tensorValues(file, t.name);
  return parameters;
}

uint32_t roundUp(uint32_t n, uint32_t multiple) {
  const uint64_t rounded = (uint64_t(n) + multiple - 1) / multiple * multiple;
  if (rounded > UINT32_MAX)
    throw gpu::GpuError("network: a guide side of " + std::to_string(n) + " pixels padded to a multiple of " +
                        std::to_string(multiple) + " is beyond 32 bits");
  return uint32_t(rounded);
}

// The smallest lightmaps the command line gives a network (a scene's or a dataset's lightmap_size): a network
// that the device cannot hold at this size is the weights' fault, not the lightmaps'.
constexpr uint32_t kSmallestGuide = 16;

// The line for a network too big for the device at the smallest lightmaps: `problem` (node `node`'s) blamed
// on the graph's size_multiple when it pads the guide past its size, else on the node's channels.
[[noreturn]] void blameTheGraph(const std::string& file, const Graph& graph, size_t node,
                                const std::string& problem, uint32_t guideWidth, uint32_t guideHeight,
                                uint32_t mapWidth, uint32_t mapHeight) {
  const std::string guide = std::to_string(guideWidth) + "×" + std::to_string(guideHeight);
  if (uint32_t(graph.sizeMultiple) > std::max(guideWidth, guideHeight))
    throw io::InputError(file, "sixway.graph.size_multiple is " + std::to_string(graph.sizeMultiple) +
                                   ": it pads " + guide + " lightmaps to " + std::to_string(mapWidth) + "×" +
                                   std::to_string(mapHeight) + ", where " + problem + "; reduce it");
  throw io::InputError(file, "sixway.graph.nodes[" + std::to_string(node) + "].out_channels is " +
                                 std::to_string(graph.nodes[node].outChannels) + ": at " + guide +
                                 " lightmaps, " + problem + "; reduce it");
}

// For each node, the 1x1 conv fused into it (or -1): a NAFBlock's only consumer, when it is a 1x1 stride-1
// conv2d without activation on the block alone.
std::vector<int> fusedProjections(const Graph& graph) {
  std::vector<int> fused(graph.nodes.size(), -1), consumers(graph.nodes.size(), 0);
  for (const Node& node : graph.nodes)
    for (const std::string& input : node.inputs) ++consumers[graph.indexOf(input)];
  for (size_t i = 0; i < graph.nodes.size(); ++i) {
    const Node& node = graph.nodes[i];
    if (node.op != Op::Conv2d || node.kernel != 1 || node.stride != 1 ||
        node.activation != Activation::None || node.inputs.size() != 1)
      continue;
    const int source = graph.indexOf(node.inputs[0]);
    if (graph.nodes[source].op == Op::NafBlock && consumers[source] == 1) fused[source] = int(i);
  }
  return fused;
}

}  // namespace

Network::Network(const gpu::Context& context, const gpu::PipelineCache& cache,
                 const io::SafetensorsFile& weights, uint32_t guideWidth, uint32_t guideHeight,
                 const NetworkOptions& options)
    : graph_(parseGraph(weights)),
      guideWidth_(guideWidth),
      guideHeight_(guideHeight),
      scene_(context, sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::FrameParameters,
             "network scene parameters") {
  if (guideWidth == 0 || guideHeight == 0) throw gpu::GpuError("network: the guide has no pixels");
  if (readsAlbedo() && !options.albedo)
    throw gpu::GpuError("network: " + weights.path.filename().string() +
                        " reads the smoke's albedo, and none was given (NetworkOptions::albedo)");
  setAlbedo(options.albedo.value_or(0.0f));
  mapWidth_ = roundUp(guideWidth, uint32_t(graph_.sizeMultiple));
  mapHeight_ = roundUp(guideHeight, uint32_t(graph_.sizeMultiple));
  pipelines_ = std::make_unique<PipelinePool>(context, cache);
  tiling_ = resolveTiling(options.tiling, context);
  const KernelSetup setup{&context, pipelines_.get(), options.precision, tiling_};
  layers_.reserve(graph_.nodes.size());
  mapOf_.assign(graph_.nodes.size(), -1);
  try {
    addLayers(context, weights, options, setup);
  } catch (const gpu::LimitError& e) {
    const size_t node = layers_.size();  // the one being built
    layers_.clear();                     // its memory, before a retry
    if (guideWidth > kSmallestGuide || guideHeight > kSmallestGuide) {
      // Throws, blaming the weights, when even the smallest lightmaps do not fit.
      const Network smallest(context, cache, weights, std::min(guideWidth, kSmallestGuide),
                             std::min(guideHeight, kSmallestGuide), options);
      throw;  // the lightmaps' size is to blame: the caller names its setting
    }
    blameTheGraph(weights.path.string(), graph_, node, e.problem(), guideWidth, guideHeight, mapWidth_,
                  mapHeight_);
  }
}

void Network::addLayers(const gpu::Context& context, const io::SafetensorsFile& weights,
                        const NetworkOptions& options, const KernelSetup& setup) {
  const std::vector<int> fused =
      options.fuseProjections ? fusedProjections(graph_) : std::vector<int>(graph_.nodes.size(), -1);
  for (const Node& node : graph_.nodes) {
    const int index = int(layers_.size());
    std::vector<int> inputs, channels;
    for (const std::string& name : node.inputs) {
      inputs.push_back(graph_.indexOf(name));
      channels.push_back(graph_.nodes[inputs.back()].outChannels);
    }
    const std::string label = weights.path.filename().string() + " " + node.name;
    auto addLayer = [&](auto kernel, std::optional<MapShape> out, double flops) {
      Layer layer{&node, std::move(kernel), std::nullopt, inputs, flops};
      if (out) {
        layer.output.emplace(context, *out, options.precision, label);
        mapOf_[index] = index;
      }
      layers_.push_back(std::move(layer));
    };
    if (std::find(fused.begin(), fused.end(), index) != fused.end()) {  // computed by the block before it
      mapOf_[index] = inputs[0];
      layers_.push_back({&node, std::monostate{}, std::nullopt, inputs, 0.0});
      continue;
    }
    // After the fused check: a fused projection's input block holds no map of its own (found by ASan).
    const MapShape in = inputs.empty() ? MapShape{} : valuesOf(inputs[0]).shape();
    switch (node.op) {
      case Op::Input: {
        const MapShape out{mapWidth_, mapHeight_, uint32_t(node.outChannels)};
        addLayer(InputKernel(setup, out, guideWidth_, guideHeight_, node.guideChannels, node.albedoChannel),
                 out, 0.0);
        break;
      }
      case Op::Conv2d:
      case Op::ConvTranspose2d: {
        ConvShape shape{in.width,
                        in.height,
                        channels,
                        node.outChannels,
                        node.kernel,
                        node.stride,
                        node.op == Op::ConvTranspose2d,
                        node.activation,
                        node.negativeSlope};
        std::vector<float> weight = tensorValues(weights, node.name + ".weight"),
                           bias = tensorValues(weights, node.name + ".bias");
        // Matrix tiling: the conv2d layers of fp16 maps on cooperative matrices, the rest as Pixels.
        if (setup.tiling == Tiling::Matrix && setup.precision == Precision::Fp16 && node.op == Op::Conv2d)
          addLayer(ConvMatrixKernel(setup, shape, weight, bias, label), shape.output(), shape.flops());
        else
          addLayer(ConvKernel(setup, shape, weight, bias, label), shape.output(), shape.flops());
        break;
      }
      case Op::UpsampleBilinear: {
        UpsampleKernel kernel(setup, in, node.factor);
        const MapShape out = kernel.output();
        addLayer(std::move(kernel), out, 0.0);
        break;
      }
      case Op::NafBlock: {
        NafShape shape{in.width, in.height, node.inChannels, node.dwExpand, node.ffnExpand, node.eps};
        ParameterMap parameters = nafParameters(weights, node);
        if (fused[index] >= 0) {
          const Node& projection = graph_.nodes[fused[index]];
          shape.projection = projection.outChannels;
          parameters["projection.weight"] = tensorValues(weights, projection.name + ".weight");
          parameters["projection.bias"] = tensorValues(weights, projection.name + ".bias");
        }
        addLayer(NafBlockKernel(setup, shape, parameters, label), shape.output(), shape.flops());
        if (fused[index] >= 0) mapOf_[index] = -1;  // the map holds the projection's values
        break;
      }
      case Op::Output:
        addLayer(OutputKernel(setup, outputLayout(node, channels, options.emission), in, guideWidth_,
                              guideHeight_),
                 std::nullopt, 0.0);
        break;
    }
  }
}

Network::~Network() = default;

void Network::setAlbedo(float albedo) {
  if (!(albedo >= 0.0f && albedo <= 1.0f))
    throw gpu::GpuError("network: the smoke's albedo must be in [0, 1] (got " + std::to_string(albedo) + ")");
  const Node& input = graph_.nodes.front();
  const float encoded = readsAlbedo() ? (albedo - input.albedoOffset) * input.albedoScale : 0.0f;
  scene_.upload(std::as_bytes(std::span(&encoded, 1)));
}

void Network::record(gpu::Sequence& sequence, const GuideImages& guide, const gpu::Image& lightmapA,
                     const gpu::Image& lightmapB, bool timeLayers) const {
  if (graph_.nodes.front().guideChannels > kGuideImageChannels && !guide.emission)
    throw gpu::GpuError("network: its guide has " + std::to_string(graph_.nodes.front().guideChannels) +
                        " channels; the 5th, the emission, needs an emission image");
  for (const gpu::Image* image : {&guide.guide, guide.emission, &lightmapA, &lightmapB})
    if (image && (image->desc().width != guideWidth_ || image->desc().height != guideHeight_))
      throw gpu::GpuError("network: " + image->desc().name + " is " + std::to_string(image->desc().width) +
                          "x" + std::to_string(image->desc().height) + ", the network was built for " +
                          std::to_string(guideWidth_) + "x" + std::to_string(guideHeight_));
  for (const Layer& layer : layers_) {
    if (std::holds_alternative<std::monostate>(layer.kernel)) continue;
    const bool naf = std::holds_alternative<NafBlockKernel>(layer.kernel);
    if (timeLayers && !naf) sequence.beginStage(layer.node->name);
    std::vector<const FeatureMap*> inputs;
    for (int i : layer.inputs) inputs.push_back(&valuesOf(i));
    std::visit(
        [&](const auto& kernel) {
          using Kernel = std::decay_t<decltype(kernel)>;
          if constexpr (std::is_same_v<Kernel, std::monostate>)
            return;
          else if constexpr (std::is_same_v<Kernel, InputKernel>)
            kernel.record(sequence, guide.guide, guide.emission, scene_, *layer.output);
          else if constexpr (std::is_same_v<Kernel, OutputKernel>)
            kernel.record(sequence, inputs, lightmapA, lightmapB);
          else if constexpr (std::is_same_v<Kernel, ConvKernel> || std::is_same_v<Kernel, ConvMatrixKernel>)
            kernel.record(sequence, inputs, *layer.output);
          else if constexpr (std::is_same_v<Kernel, NafBlockKernel>)
            kernel.record(sequence, *inputs.at(0), *layer.output, timeLayers ? layer.node->name : "");
          else
            kernel.record(sequence, *inputs.at(0), *layer.output);
        },
        layer.kernel);
    if (timeLayers && !naf) sequence.endStage();
  }
}

uint32_t Network::stageCount() const {
  uint32_t stages = 0;
  for (const Layer& layer : layers_)
    if (!std::holds_alternative<std::monostate>(layer.kernel))
      stages += std::holds_alternative<NafBlockKernel>(layer.kernel) ? NafBlockKernel::kStages : 1;
  return stages;
}

const FeatureMap& Network::valuesOf(int node) const {
  return *layers_[mapOf_[node]].output;
}

const FeatureMap* Network::featureMap(const std::string& node) const {
  const int index = graph_.indexOf(node);
  if (index < 0) throw gpu::GpuError("network: no node '" + node + "'");
  return mapOf_[index] < 0 ? nullptr : &*layers_[mapOf_[index]].output;
}

std::vector<LayerInfo> Network::layers() const {
  std::vector<LayerInfo> info;
  for (const Layer& layer : layers_) {
    if (std::holds_alternative<std::monostate>(layer.kernel)) continue;  // timed with its block
    const Node& node = *layer.node;
    std::string kind(opName(node.op));
    if (node.op == Op::Conv2d || node.op == Op::ConvTranspose2d) {
      const std::string k = std::to_string(node.kernel);
      kind += ' ' + k + 'x' + k;
      if (node.op == Op::Conv2d && node.stride == 2) kind += " s2";
    }
    info.push_back({node.name, kind, layer.flops, {}});
    if (const auto* naf = std::get_if<NafBlockKernel>(&layer.kernel)) {
      const std::array<double, 4> flops = naf->shape().kernelFlops();
      info.back().parts = {
          {"norm_expand", flops[0]}, {"dw_gate", flops[1]}, {"attention", flops[2]}, {"tail", flops[3]}};
    }
  }
  return info;
}

}  // namespace sixway::nn
