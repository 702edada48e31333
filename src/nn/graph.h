#pragma once
// The network graph stored in a weights file's metadata (`sixway.graph`, docs/network-format.md): a list
// of nodes, each one operator with named inputs, checked against each other and against the file's tensors.
#include <array>
#include <string>
#include <vector>

#include "io/safetensors.h"

namespace sixway::nn {

enum class Op { Input, Conv2d, ConvTranspose2d, UpsampleBilinear, NafBlock, Output };

// The values are those of shaders/common/nn_activation.glsl.
enum class Activation { None = 0, Relu = 1, LeakyRelu = 2, Gelu = 3, Silu = 4 };

enum class Encoding { Linear, Srgb };

struct Node {
  std::string name;
  Op op = Op::Input;
  std::vector<std::string> inputs;  // concatenated along channels, in this order
  int inChannels = 0, outChannels = 0;
  int scale = 1;  // the input's size over this node's output size

  // conv2d, conv_transpose2d
  int kernel = 1, stride = 1;
  Activation activation = Activation::None;
  float negativeSlope = 0.0f;  // leaky_relu
  // upsample_bilinear
  int factor = 2;
  // naf_block
  int dwExpand = 2, ffnExpand = 2;
  float eps = 1e-6f;
  // input
  int guideChannels = 3;              // 4: with the fine alpha; 5: and the emission (kGuideImageChannels)
  float guideAlphaStepVoxels = 0.0f;  // > 0: channel 4 is the guide's fine alpha of this step
  // The smoke's single-scattering albedo as an input: channel albedoChannel (the one after the guide's; -1:
  // none) holds (albedo - albedoOffset) * albedoScale over the whole map (NetworkOptions::albedo).
  int albedoChannel = -1;
  float albedoOffset = 0.0f, albedoScale = 1.0f;
  // output: the eight channels (names, encodings) and the lightmaps' components as indices into them
  std::vector<std::string> channels;
  std::vector<Encoding> encodings;
  std::array<int, 4> lightmapA{}, lightmapB{};

  int gatedChannels() const { return inChannels * dwExpand / 2; }  // NAFBlock: after the first SimpleGate
  int ffnChannels() const { return inChannels * ffnExpand / 2; }   // NAFBlock: after the second
};

// The guiding map image holds the guide's first 4 channels; a 5th, the direct emission, is a second image.
inline constexpr int kGuideImageChannels = 4;
inline constexpr int kMaxGuideChannels = 5;

// Bounds on the values a weights file stores. Trained networks stay within a few units (the shipped ones
// reach 2.1); a finite value near a float's limit overflows to Inf in the first layer and to NaN after it.
inline constexpr float kMaxWeightMagnitude = 1e4f;
// leaky_relu's negative_slope is in [0, kMaxLeakySlope].
inline constexpr double kMaxLeakySlope = 1.0;
// naf_block's eps is kept far from a float's denormals, which a GPU may flush to 0: a flat patch would then
// divide 0 by 0.
inline constexpr double kMinNormEpsilon = 1e-12;
inline constexpr double kMaxNormEpsilon = 1.0;

// size_multiple and every node's scale are at most the largest lightmap side (a scene's
// render.lightmap_size): beyond it a map is one pixel, or a guide is padded past any lightmap. It also keeps
// the sizes computed from them far from overflow.
inline constexpr int kMaxSizeMultiple = 4096;

struct Graph {
  int version = 1;
  int sizeMultiple = 1;     // input sizes must be a multiple of it (the runner pads)
  std::vector<Node> nodes;  // in evaluation order: "input" first, "output" last

  const Node& node(const std::string& name) const;
  int indexOf(const std::string& name) const;  // -1 when absent
};

// A tensor that a node needs: its name in the file and its shape.
struct TensorRequirement {
  std::string name;
  std::vector<int64_t> shape;
};
std::vector<TensorRequirement> requiredTensors(const Node& node);

// Reads `sixway.graph` from the file's metadata and checks it: known operators, inputs defined before use,
// channel counts and scales that agree, every required tensor present with its shape, and a float dtype.
// Throws io::InputError "<file>: <problem>" on the first problem.
Graph parseGraph(const io::SafetensorsFile& file);

// The graph of `file` parsed from JSON text (for tests of the schema), without the tensor checks.
Graph parseGraphJson(const std::string& text, const std::string& source);

std::string_view opName(Op op);

}  // namespace sixway::nn
