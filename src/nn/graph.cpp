#include "nn/graph.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/error.h"
#include "io/json_reader.h"
#include "scene/scene.h"

namespace sixway::nn {
namespace {

const io::Choices<Op> kOps = {{"input", Op::Input},
                              {"conv2d", Op::Conv2d},
                              {"conv_transpose2d", Op::ConvTranspose2d},
                              {"upsample_bilinear", Op::UpsampleBilinear},
                              {"naf_block", Op::NafBlock},
                              {"output", Op::Output}};
const io::Choices<Activation> kActivations = {{"none", Activation::None},
                                              {"relu", Activation::Relu},
                                              {"leaky_relu", Activation::LeakyRelu},
                                              {"gelu", Activation::Gelu},
                                              {"silu", Activation::Silu}};
const io::Choices<Encoding> kEncodings = {{"linear", Encoding::Linear}, {"srgb", Encoding::Srgb}};

Op readOp(io::JsonReader& r) {
  const std::string name = r.required<std::string>("op");
  for (const auto& [spelling, op] : kOps)
    if (spelling == name) return op;
  std::string known;
  for (const auto& choice : kOps) known += (known.empty() ? "" : ", ") + std::string(choice.first);
  r.fail("op", "unknown layer type \"" + name + "\" (known: " + known + ")");
}

void readConv(io::JsonReader& r, Node& n) {
  n.kernel = r.required<int>("kernel");
  n.stride = r.required<int>("stride");
  n.activation = r.choice("activation", kActivations);
  if (n.activation == Activation::LeakyRelu)
    n.negativeSlope = r.required<float>("negative_slope", io::inRange(0, kMaxLeakySlope));
  if (n.op == Op::Conv2d) {
    if (n.kernel != 1 && n.kernel != 3) r.fail("kernel", "must be 1 or 3 (got " + io::show(n.kernel) + ")");
    if (n.stride != 1 && n.stride != 2) r.fail("stride", "must be 1 or 2 (got " + io::show(n.stride) + ")");
  } else if (n.kernel != 2 || n.stride != 2) {
    r.fail("kernel", "conv_transpose2d supports kernel 2, stride 2 only");
  }
}

std::array<int, 4> readPacking(io::JsonReader& r, std::string_view key,
                               const std::vector<std::string>& channels) {
  const auto names = r.required<std::vector<std::string>>(key);
  if (names.size() != 4) r.fail(key, "needs 4 channel names");
  std::array<int, 4> indices{};
  for (int i = 0; i < 4; ++i) {
    const auto it = std::find(channels.begin(), channels.end(), names[i]);
    if (it == channels.end()) r.fail(key, "\"" + names[i] + "\" is not one of the output's channels");
    indices[i] = static_cast<int>(it - channels.begin());
  }
  return indices;
}

void readOutput(io::JsonReader& r, Node& n) {
  n.channels = r.required<std::vector<std::string>>("channels");
  if (n.channels.size() != 8) r.fail("channels", "needs the 8 lightmap channels");
  const auto encodings = r.required<std::vector<std::string>>("encoding");
  if (encodings.size() != 8) r.fail("encoding", "needs one encoding per channel");
  for (const std::string& e : encodings) n.encodings.push_back(r.pick("encoding", e, kEncodings));
  r.object("packing", [&](io::JsonReader& p) {
    n.lightmapA = readPacking(p, "A", n.channels);
    n.lightmapB = readPacking(p, "B", n.channels);
    return 0;
  });
}

Node readNode(io::JsonReader& r) {
  Node n;
  n.name = r.required<std::string>("name");
  n.op = readOp(r);
  n.scale = r.required<int>("scale", io::inRange(1, kMaxSizeMultiple));
  n.outChannels = r.optional<int>("out_channels", 0, io::positive());
  if (n.op == Op::Input) {
    n.outChannels = r.required<int>("out_channels", io::inRange(1, 8));
    n.guideChannels =
        r.required<int>("guide_channels", io::inRange(1, std::min(n.outChannels, kMaxGuideChannels)));
    // The guide's 4th channel is the fine alpha, its 5th the emission of the same fine march, which the
    // runtime's guide computes only when asked.
    n.guideAlphaStepVoxels =
        r.optional<float>("guide_alpha_step_voxels", 0.0f,
                          io::zeroOrInRange(scene::kMinGuideStepVoxels, scene::kMaxGuideStepVoxels));
    if ((n.guideChannels >= 4) != (n.guideAlphaStepVoxels > 0.0f))
      r.fail("guide_channels",
             "a 4th guide channel is the fine alpha: guide_channels 4 or 5 go with "
             "guide_alpha_step_voxels > 0");
    r.optionalObject("albedo", [&](io::JsonReader& a) {
      n.albedoChannel = a.required<int>("channel");
      if (n.albedoChannel != n.guideChannels)
        a.fail("channel", "must be the one after the guide's, " + io::show(n.guideChannels) + " (got " +
                              io::show(n.albedoChannel) + ")");
      if (n.albedoChannel >= n.outChannels) a.fail("channel", "is past the input's out_channels");
      n.albedoOffset = a.required<float>("offset", io::inRange(-1e6, 1e6));
      n.albedoScale = a.required<float>("scale", io::inRange(-1e6, 1e6));
      if (n.albedoScale == 0.0f) a.fail("scale", "must not be 0");
      return 0;
    });
    return n;
  }
  n.inputs = r.required<std::vector<std::string>>("inputs");
  if (n.inputs.empty()) r.fail("inputs", "needs at least one input");
  n.inChannels = r.required<int>("in_channels", io::positive());
  if (n.op != Op::Output && n.outChannels == 0) r.required<int>("out_channels");  // reports it missing
  switch (n.op) {
    case Op::Conv2d:
    case Op::ConvTranspose2d:
      readConv(r, n);
      break;
    case Op::UpsampleBilinear:
      n.factor = r.required<int>("factor", io::inRange(2, 8));
      break;
    case Op::NafBlock:
      n.dwExpand = r.required<int>("dw_expand", io::inRange(1, 8));
      n.ffnExpand = r.required<int>("ffn_expand", io::inRange(1, 8));
      n.eps = r.required<float>("eps", io::inRange(kMinNormEpsilon, kMaxNormEpsilon));
      if (n.inChannels * n.dwExpand % 2 || n.inChannels * n.ffnExpand % 2)
        r.fail("dw_expand", "channels times dw_expand and ffn_expand must be even (SimpleGate halves them)");
      break;
    case Op::Output:
      readOutput(r, n);
      break;
    case Op::Input:
      break;
  }
  return n;
}

// The node's output channels and scale follow from its inputs; these checks catch a graph that does not add
// up.
void checkNode(const Graph& g, const Node& n, io::JsonReader& r) {
  if (n.op == Op::Input) {
    if (n.scale != 1) r.fail("scale", "the input is at scale 1");
    return;
  }
  int channels = 0, scale = 0;
  for (const std::string& name : n.inputs) {
    const int index = g.indexOf(name);
    if (index < 0) r.fail("inputs", "\"" + name + "\" is not an earlier node");
    const Node& input = g.nodes[index];
    if (input.op == Op::Output) r.fail("inputs", "the output node cannot be an input");
    if (scale != 0 && input.scale != scale) r.fail("inputs", "concatenated inputs differ in scale");
    scale = input.scale;
    channels += input.outChannels;
  }
  if (channels != n.inChannels)
    r.fail("in_channels", "is " + io::show(n.inChannels) + " but the inputs have " + io::show(channels));
  int expected = scale;
  if (n.op == Op::Conv2d) expected = scale * n.stride;
  if (n.op == Op::ConvTranspose2d || n.op == Op::UpsampleBilinear) {
    const int factor = n.op == Op::UpsampleBilinear ? n.factor : n.stride;
    if (scale % factor) r.fail("scale", "upsampling past the input's size");
    expected = scale / factor;
  }
  if (n.scale != expected)
    r.fail("scale", "is " + io::show(n.scale) + ", the inputs give " + io::show(expected));
  if (n.op == Op::NafBlock && n.outChannels != n.inChannels)
    r.fail("out_channels", "a naf_block keeps its channel count");
  if (n.op == Op::UpsampleBilinear && n.outChannels != n.inChannels)
    r.fail("out_channels", "upsampling keeps the channel count");
  if (n.op == Op::Output) {
    if (n.inChannels != 8) r.fail("in_channels", "the output takes 8 channels");
    if (n.inputs.size() > 4) r.fail("inputs", "the output takes at most 4 inputs");
    if (n.scale != 1) r.fail("scale", "the output is at the input's size");
    for (const std::string& name : n.inputs)
      if (g.node(name).outChannels > 4) r.fail("inputs", "each output input has at most 4 channels");
  }
}

Graph readGraph(io::JsonReader& r) {
  Graph g;
  g.version = r.required<int>("version");
  if (g.version != 1)
    r.fail("version", "this sixway reads graph version 1 (got " + io::show(g.version) + ")");
  g.sizeMultiple = r.required<int>("size_multiple", io::inRange(1, kMaxSizeMultiple));
  r.requiredObjects(
      "nodes",
      [&g](io::JsonReader& nr) {
        Node n = readNode(nr);
        if (g.indexOf(n.name) >= 0) nr.fail("name", "\"" + n.name + "\" names two nodes");
        if ((n.op == Op::Input) != g.nodes.empty())
          nr.fail("op",
                  g.nodes.empty() ? "the first node must be the input" : "only the first node is the input");
        if (!g.nodes.empty() && g.nodes.back().op == Op::Output)
          nr.fail("op", "the output must be the last node");
        checkNode(g, n, nr);
        g.nodes.push_back(std::move(n));
        return 0;
      },
      2);
  if (g.nodes.back().op != Op::Output) r.fail("nodes", "the last node must be the output");
  return g;
}

std::vector<int64_t> shapeOf(std::initializer_list<int> dims) {
  return std::vector<int64_t>(dims.begin(), dims.end());
}

std::string showShape(const std::vector<int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

// A diverged training exports NaN/Inf or huge weights, which would turn every frame into NaN pixels.
void checkWeightValues(const std::string& source, const std::string& tensorName,
                       const std::vector<float>& values) {
  const auto broken = [](float v) { return !std::isfinite(v) || std::abs(v) > kMaxWeightMagnitude; };
  const auto bad = std::ranges::find_if(values, broken);
  if (bad == values.end()) return;
  const std::string value = std::isnan(*bad) ? "NaN" : std::isinf(*bad) ? "Inf" : io::show(*bad);
  const std::string bound = std::isfinite(*bad) ? ", beyond ±" + io::show(kMaxWeightMagnitude) : "";
  throw io::InputError(source, "tensor '" + tensorName + "' holds " + value + " at element " +
                                   std::to_string(bad - values.begin()) + bound +
                                   ": the weights are broken (a diverged training?)");
}

}  // namespace

const Node& Graph::node(const std::string& name) const {
  return nodes.at(static_cast<std::size_t>(indexOf(name)));
}

int Graph::indexOf(const std::string& name) const {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<TensorRequirement> requiredTensors(const Node& n) {
  const std::string& p = n.name;
  const int c = n.inChannels, o = n.outChannels;
  switch (n.op) {
    case Op::Conv2d:
      return {{p + ".weight", shapeOf({o, c, n.kernel, n.kernel})}, {p + ".bias", shapeOf({o})}};
    case Op::ConvTranspose2d:
      return {{p + ".weight", shapeOf({c, o, n.kernel, n.kernel})}, {p + ".bias", shapeOf({o})}};
    case Op::NafBlock: {
      const int dw = c * n.dwExpand, ffn = c * n.ffnExpand;
      return {{p + ".norm1.weight", shapeOf({c})},
              {p + ".norm1.bias", shapeOf({c})},
              {p + ".conv1.weight", shapeOf({dw, c, 1, 1})},
              {p + ".conv1.bias", shapeOf({dw})},
              {p + ".conv2.weight", shapeOf({dw, 1, 3, 3})},
              {p + ".conv2.bias", shapeOf({dw})},
              {p + ".sca.weight", shapeOf({dw / 2, dw / 2, 1, 1})},
              {p + ".sca.bias", shapeOf({dw / 2})},
              {p + ".conv3.weight", shapeOf({c, dw / 2, 1, 1})},
              {p + ".conv3.bias", shapeOf({c})},
              {p + ".norm2.weight", shapeOf({c})},
              {p + ".norm2.bias", shapeOf({c})},
              {p + ".conv4.weight", shapeOf({ffn, c, 1, 1})},
              {p + ".conv4.bias", shapeOf({ffn})},
              {p + ".conv5.weight", shapeOf({c, ffn / 2, 1, 1})},
              {p + ".conv5.bias", shapeOf({c})},
              {p + ".beta", shapeOf({1, c, 1, 1})},
              {p + ".gamma", shapeOf({1, c, 1, 1})}};
    }
    default:
      return {};
  }
}

Graph parseGraphJson(const std::string& text, const std::string& source) {
  const nlohmann::json json = io::parseJsonText(text, source + ": sixway.graph");
  io::JsonReader reader(json, "sixway.graph", source);
  Graph graph = readGraph(reader);
  reader.finish();
  return graph;
}

Graph parseGraph(const io::SafetensorsFile& file) {
  const std::string source = file.path.string();
  const auto it = file.metadata.find("sixway.graph");
  if (it == file.metadata.end())
    throw io::InputError(source, "no \"sixway.graph\" in the metadata: not a sixway network");
  Graph graph = parseGraphJson(it->second, source);
  for (const Node& node : graph.nodes)
    for (const TensorRequirement& required : requiredTensors(node)) {
      const io::Tensor& tensor = file.at(required.name);
      if (tensor.shape != required.shape)
        throw io::InputError(source, "tensor '" + required.name + "' has shape " + showShape(tensor.shape) +
                                         ", node '" + node.name + "' needs " + showShape(required.shape));
      if (tensor.dtype != io::DType::F32 && tensor.dtype != io::DType::F16 && tensor.dtype != io::DType::BF16)
        throw io::InputError(source, "tensor '" + required.name + "' is " +
                                         std::string(io::dtypeName(tensor.dtype)) +
                                         ", weights must be F32, F16 or BF16");
      checkWeightValues(source, required.name, tensor.toFloat());
    }
  return graph;
}

std::string_view opName(Op op) {
  for (const auto& [spelling, value] : kOps)
    if (value == op) return spelling;
  return "?";
}

}  // namespace sixway::nn
