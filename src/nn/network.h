#pragma once
// The lightmap network run by our own compute shaders, built from a weights file alone: the graph in its
// metadata gives the layers, the tensors their weights. Everything (pipelines, weights, feature maps) is made
// once for one guide size; record() puts the whole network into a Sequence that is then replayed per frame.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/buffer.h"
#include "io/safetensors.h"
#include "nn/feature_map.h"
#include "nn/graph.h"
#include "nn/kernel.h"

namespace sixway::gpu {
class Context;
class Image;
class PipelineCache;
class Sequence;
}  // namespace sixway::gpu

namespace sixway::nn {

struct NetworkOptions {
  Precision precision = Precision::Fp32;
  // A 1x1 conv (no activation) that is the only consumer of a NAFBlock runs inside the block's last kernel
  // (an adapter's head): the block's own output is then never stored, and has no feature map.
  bool fuseProjections = true;
  Tiling tiling = Tiling::Device;  // work per invocation (nn/kernel.h)
  // False for smoke that emits nothing (a scene without emission): the lightmaps' emissive is then 0 whatever
  // the network's head holds, which on such smoke can only be spurious glow (docs/network-format.md).
  bool emission = true;
  // The smoke's single-scattering albedo (the scene's smoke.albedo), for a graph whose input reads it (its
  // input node's "albedo"); such a network cannot be built without it. Network::setAlbedo changes it.
  std::optional<float> albedo;
};

// A layer as the benchmark sees it: one timed stage, or one per kernel (`parts`, in stage order).
struct LayerInfo {
  struct Part {
    std::string name;  // the stage is "<layer>/<part>"
    double flops;
  };
  std::string name;
  std::string kind;  // the layer type for per-type figures: "conv2d 3x3", "conv2d 3x3 s2", "naf_block", ...
  double flops;      // 2 per multiply-add of its convolutions (docs/benchmarks.md)
  std::vector<Part> parts;
};

// The network's input images: the guiding map (RGBA16F/32F) and, for a graph whose guide has 5 channels,
// its direct emission (any float format; channel R), both of the guide's size.
struct GuideImages {
  GuideImages(const gpu::Image& guide, const gpu::Image* emission = nullptr)
      : guide(guide), emission(emission) {}
  const gpu::Image& guide;
  const gpu::Image* emission;
};

class Network {
 public:
  // Throws io::InputError naming the file when the graph or a tensor is wrong, or when the device cannot
  // hold the network even at 16×16 lightmaps (naming the graph's size_multiple or a node's channels);
  // gpu::LimitError when it cannot at this guide's size but can at 16×16.
  Network(const gpu::Context& context, const gpu::PipelineCache& cache, const io::SafetensorsFile& weights,
          uint32_t guideWidth, uint32_t guideHeight, const NetworkOptions& options = {});
  ~Network();
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  const Graph& graph() const { return graph_; }
  // Whether the input reads the smoke's albedo (NetworkOptions::albedo).
  bool readsAlbedo() const { return graph_.nodes.front().albedoChannel >= 0; }
  // The albedo that the next submission or recording into a command buffer reads (a frame parameter: the
  // recorded work need not change); for a network that does not read it, ignored. Throws gpu::GpuError
  // outside [0, 1].
  void setAlbedo(float albedo);
  // The feature maps' size: the guide's, rounded up to the graph's size multiple.
  uint32_t mapWidth() const { return mapWidth_; }
  uint32_t mapHeight() const { return mapHeight_; }
  Tiling tiling() const { return tiling_; }  // resolved: Blocks, Pixels or Matrix

  // The guide in, lightmaps A and B (any float RGBA storage format, the guide's size) out. With
  // `timeLayers`, every node is a timed stage named after it, and a NAFBlock is four stages
  // "<node>/<kernel>". Throws gpu::GpuError for an image of another size, or without the emission image
  // that a 5-channel guide needs.
  void record(gpu::Sequence& sequence, const GuideImages& guide, const gpu::Image& lightmapA,
              const gpu::Image& lightmapB, bool timeLayers = false) const;
  // Stages that record(..., true) adds.
  uint32_t stageCount() const;

  // The output of a node after a submitted recording, for tests and tools; nullptr for the output node and
  // for a NAFBlock whose projection was fused.
  const FeatureMap* featureMap(const std::string& node) const;
  std::vector<LayerInfo> layers() const;

 private:
  struct Layer;
  Graph graph_;
  uint32_t guideWidth_, guideHeight_, mapWidth_, mapHeight_;
  Tiling tiling_;
  std::unique_ptr<PipelinePool> pipelines_;  // outlives the layers that use its pipelines
  gpu::Buffer scene_;                        // the input's encoded albedo (a frame parameter)
  std::vector<Layer> layers_;                // one per node
  std::vector<int> mapOf_;                   // per node: the layer whose feature map holds its values, or -1
  const FeatureMap& valuesOf(int node) const;
  void addLayers(const gpu::Context& context, const io::SafetensorsFile& weights,
                 const NetworkOptions& options, const KernelSetup& setup);
};

}  // namespace sixway::nn
