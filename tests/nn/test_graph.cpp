// The graph in a weights file's metadata: the committed test networks parse; malformed files (missing
// tensor, wrong shape, unknown layer type, bad JSON, a graph that does not add up) fail with one line that
// names the file and the problem.
#include <gmock/gmock.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>

#include "gpu/check.h"
#include "gpu/pipeline.h"
#include "io/json_reader.h"
#include "io/safetensors.h"
#include "nn/graph.h"
#include "nn/network.h"
#include "support/gpu_fixture.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

const std::filesystem::path kTiny = std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn" / "tiny.safetensors";
const std::filesystem::path kDefault =
    std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn" / "default.safetensors";

TEST(NetworkGraph, DefaultNetworkHasTheIssuesShape) {
  const nn::Graph graph = nn::parseGraph(io::readSafetensors(kDefault));
  EXPECT_EQ(graph.sizeMultiple, 4);
  EXPECT_EQ(graph.nodes.front().op, nn::Op::Input);
  EXPECT_EQ(graph.nodes.back().op, nn::Op::Output);
  int nafBlocks = 0, heads = 0;
  for (const nn::Node& node : graph.nodes) {
    nafBlocks += node.op == nn::Op::NafBlock;
    heads += node.name.ends_with(".head");
  }
  EXPECT_EQ(nafBlocks, 4);  // one per adapter
  EXPECT_EQ(heads, 4);
  EXPECT_EQ(graph.node("mid.1").outChannels, 64);
  EXPECT_EQ(graph.node("dec.1.0").inputs, (std::vector<std::string>{"up.1", "enc.1.1"}));  // skip connection
}

// Rewrites the tiny network with `edit` applied to its tensors and graph JSON, and returns the error of
// parsing it.
class MalformedWeights : public ::testing::Test {
 protected:
  std::string errorAfter(const std::function<void(std::vector<io::Tensor>&, nlohmann::json&)>& edit) {
    io::SafetensorsFile file = io::readSafetensors(kTiny);
    nlohmann::json graph = nlohmann::json::parse(file.metadata.at("sixway.graph"));
    edit(file.tensors, graph);
    file.metadata["sixway.graph"] = graph.dump();
    io::writeSafetensors(path(), file.tensors, file.metadata);
    return inputErrorMessage([this] { nn::parseGraph(io::readSafetensors(path())); });
  }
  std::filesystem::path path() const { return dir_ / "net.safetensors"; }
  nlohmann::json& node(nlohmann::json& graph, const std::string& name) {
    for (nlohmann::json& n : graph["nodes"])
      if (n["name"] == name) return n;
    throw std::logic_error("no node " + name);
  }

  TempDir dir_;
};

TEST_F(MalformedWeights, MissingTensor) {
  const std::string error = errorAfter([](std::vector<io::Tensor>& tensors, nlohmann::json&) {
    std::erase_if(tensors, [](const io::Tensor& t) { return t.name == "adapters.2.blocks.0.conv4.bias"; });
  });
  EXPECT_THAT(error, namesFileAndProblem(path(), "missing tensor 'adapters.2.blocks.0.conv4.bias'"));
}

TEST_F(MalformedWeights, WrongShape) {
  const std::string error = errorAfter([](std::vector<io::Tensor>& tensors, nlohmann::json&) {
    for (io::Tensor& t : tensors)
      if (t.name == "enc.0.0.weight")
        t = io::Tensor::fromFloat(t.name, io::DType::F32, {7, 4, 1, 9}, t.toFloat());
  });
  EXPECT_THAT(error, namesFileAndProblem(path(),
                                         "tensor 'enc.0.0.weight' has shape [7, 4, 1, 9], node 'enc.0.0' "
                                         "needs [7, 4, 3, 3]"));
}

// Weights holding NaN or Inf are refused: accepted, every frame would come out NaN.
TEST_F(MalformedWeights, NotFiniteWeights) {
  for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const std::string error = errorAfter([bad](std::vector<io::Tensor>& tensors, nlohmann::json&) {
      for (io::Tensor& t : tensors)
        if (t.name == "enc.0.0.weight") {
          std::vector<float> values = t.toFloat();
          values[5] = bad;
          t = io::Tensor::fromFloat(t.name, io::DType::F32, t.shape, values);
        }
    });
    EXPECT_THAT(error, namesFileAndProblem(path(), std::string("tensor 'enc.0.0.weight' holds ") +
                                                       (std::isnan(bad) ? "NaN" : "Inf") + " at element 5"));
  }
}

// Finite but huge weights overflowed to Inf in the first layer and gave NaN pixels.
TEST_F(MalformedWeights, HugeFiniteWeights) {
  for (const float huge : {3e38f, -2e4f}) {
    const std::string error = errorAfter([huge](std::vector<io::Tensor>& tensors, nlohmann::json&) {
      for (io::Tensor& t : tensors)
        if (t.name == "adapters.1.blocks.0.beta") {
          std::vector<float> values = t.toFloat();
          values[3] = huge;
          t = io::Tensor::fromFloat(t.name, io::DType::F32, t.shape, values);
        }
    });
    EXPECT_THAT(error, namesFileAndProblem(path(), "tensor 'adapters.1.blocks.0.beta' holds " +
                                                       io::show(huge) + " at element 3, beyond ±10000"));
  }
}

TEST_F(MalformedWeights, LeakySlopeBeyondOne) {
  for (const double slope : {1e30, -0.5}) {
    const std::string error = errorAfter([this, slope](std::vector<io::Tensor>&, nlohmann::json& graph) {
      node(graph, "enc.0.0")["activation"] = "leaky_relu";
      node(graph, "enc.0.0")["negative_slope"] = slope;
    });
    EXPECT_THAT(error, namesFileAndProblem(path(), "negative_slope: must be in [0, 1] (got " +
                                                       io::show(static_cast<float>(slope)) + ")"));
  }
}

// An eps that a GPU may flush to 0 divides 0 by 0 on a flat patch.
TEST_F(MalformedWeights, NormEpsilonOutsideItsRange) {
  for (const double eps : {1e-30, 1e30}) {
    const std::string error = errorAfter([this, eps](std::vector<io::Tensor>&, nlohmann::json& graph) {
      node(graph, "adapters.0.blocks.0")["eps"] = eps;
    });
    EXPECT_THAT(error, namesFileAndProblem(path(), "eps: must be in [1e-12, 1] (got " +
                                                       io::show(static_cast<float>(eps)) + ")"));
  }
}

TEST_F(MalformedWeights, UnknownLayerType) {
  const std::string error = errorAfter(
      [this](std::vector<io::Tensor>&, nlohmann::json& graph) { node(graph, "mid.0")["op"] = "conv9d"; });
  EXPECT_THAT(error, namesFileAndProblem(path(), "sixway.graph.nodes[7].op: unknown layer type \"conv9d\""));
}

TEST_F(MalformedWeights, ChannelsThatDoNotAddUp) {
  const std::string error = errorAfter([this](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "dec.1.0")["inputs"] = {"up.1"};
  });
  EXPECT_THAT(error, namesFileAndProblem(path(), "in_channels: is 20 but the inputs have 10"));
}

TEST_F(MalformedWeights, InputThatIsNotAnEarlierNode) {
  const std::string error = errorAfter([this](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "enc.0.0")["inputs"] = {"mid.1"};
  });
  EXPECT_THAT(error, namesFileAndProblem(path(), "\"mid.1\" is not an earlier node"));
}

TEST_F(MalformedWeights, UnknownKey) {
  const std::string error = errorAfter(
      [this](std::vector<io::Tensor>&, nlohmann::json& graph) { node(graph, "mid.0")["kernal"] = 3; });
  EXPECT_THAT(error, namesFileAndProblem(path(), "kernal: unknown key"));
}

// The guide's 4th channel is the fine alpha: reading it needs the step the runtime's guide marches with.
TEST_F(MalformedWeights, FourGuideChannelsNeedTheFineAlphaStep) {
  const std::string error = errorAfter([this](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["guide_channels"] = 4;
  });
  EXPECT_THAT(error, namesFileAndProblem(path(), "guide_channels: a 4th guide channel is the fine alpha"));
  const std::string negative = errorAfter([this](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["guide_alpha_step_voxels"] = -1;
  });
  EXPECT_THAT(negative,
              namesFileAndProblem(path(), "guide_alpha_step_voxels: must be 0 or in [0.05, 16] (got -1)"));
  // A billionth of a cell never advances the fine march's float ray: an empty guide, the smoke gone.
  const std::string tiny = errorAfter([this](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["guide_channels"] = 4;
    node(graph, "input")["guide_alpha_step_voxels"] = 1e-9;
  });
  EXPECT_THAT(tiny,
              namesFileAndProblem(path(), "guide_alpha_step_voxels: must be 0 or in [0.05, 16] (got 1e-09)"));
  io::SafetensorsFile file = io::readSafetensors(kTiny);
  nlohmann::json json = nlohmann::json::parse(file.metadata.at("sixway.graph"));
  node(json, "input")["guide_channels"] = 4;
  node(json, "input")["guide_alpha_step_voxels"] = 0.5;
  file.metadata["sixway.graph"] = json.dump();
  io::writeSafetensors(path(), file.tensors, file.metadata);
  const nn::Graph graph = nn::parseGraph(io::readSafetensors(path()));
  EXPECT_EQ(graph.nodes.front().guideChannels, 4);
  EXPECT_FLOAT_EQ(graph.nodes.front().guideAlphaStepVoxels, 0.5f);
  EXPECT_FLOAT_EQ(nn::parseGraph(io::readSafetensors(kTiny)).nodes.front().guideAlphaStepVoxels, 0.0f);
}

// The smoke's albedo as an input: in the channel after the guide's, with a nonzero scale.
TEST_F(MalformedWeights, AlbedoInputInTheChannelAfterTheGuide) {
  const nlohmann::json albedo = {{"channel", 3}, {"offset", 0.875}, {"scale", 13.5}};
  const std::string wrongChannel = errorAfter([&](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["albedo"] = albedo;
    node(graph, "input")["albedo"]["channel"] = 2;
  });
  EXPECT_THAT(wrongChannel,
              namesFileAndProblem(path(), "albedo.channel: must be the one after the guide's, 3 (got 2)"));
  const std::string zeroScale = errorAfter([&](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["albedo"] = albedo;
    node(graph, "input")["albedo"]["scale"] = 0;
  });
  EXPECT_THAT(zeroScale, namesFileAndProblem(path(), "albedo.scale: must not be 0"));
  const std::string noOffset = errorAfter([&](std::vector<io::Tensor>&, nlohmann::json& graph) {
    node(graph, "input")["albedo"] = {{"channel", 3}, {"scale", 2}};
  });
  EXPECT_THAT(noOffset, namesFileAndProblem(path(), "albedo.offset"));
  io::SafetensorsFile file = io::readSafetensors(kTiny);
  nlohmann::json json = nlohmann::json::parse(file.metadata.at("sixway.graph"));
  node(json, "input")["albedo"] = albedo;
  file.metadata["sixway.graph"] = json.dump();
  io::writeSafetensors(path(), file.tensors, file.metadata);
  const nn::Node input = nn::parseGraph(io::readSafetensors(path())).nodes.front();
  EXPECT_EQ(input.albedoChannel, 3);
  EXPECT_FLOAT_EQ(input.albedoOffset, 0.875f);
  EXPECT_FLOAT_EQ(input.albedoScale, 13.5f);
  EXPECT_EQ(nn::parseGraph(io::readSafetensors(kTiny)).nodes.front().albedoChannel, -1);
}

TEST_F(MalformedWeights, BadGraphJson) {
  io::SafetensorsFile file = io::readSafetensors(kTiny);
  file.metadata["sixway.graph"] = "{\"version\": 1, \"nodes\": [";
  io::writeSafetensors(path(), file.tensors, file.metadata);
  EXPECT_THAT(inputErrorMessage([this] { nn::parseGraph(io::readSafetensors(path())); }),
              namesFileAndProblem(path(), "sixway.graph: invalid JSON"));
}

TEST_F(MalformedWeights, NoGraph) {
  io::SafetensorsFile file = io::readSafetensors(kTiny);
  file.metadata.erase("sixway.graph");
  io::writeSafetensors(path(), file.tensors, file.metadata);
  EXPECT_THAT(inputErrorMessage([this] { nn::parseGraph(io::readSafetensors(path())); }),
              namesFileAndProblem(path(), "no \"sixway.graph\" in the metadata"));
}

// A size multiple past the largest lightmap padded a 16² guide to a map whose size wrapped 32 bits.
TEST_F(MalformedWeights, SizeMultipleAndScaleWithinTheLargestLightmap) {
  std::string error = errorAfter(
      [](std::vector<io::Tensor>&, nlohmann::json& graph) { graph["size_multiple"] = 1000000000; });
  EXPECT_THAT(error, namesFileAndProblem(
                         path(), "sixway.graph.size_multiple: must be in [1, 4096] (got 1000000000)"));
  error = errorAfter(
      [this](std::vector<io::Tensor>&, nlohmann::json& graph) { node(graph, "down.0")["scale"] = 8192; });
  EXPECT_THAT(error, namesFileAndProblem(path(), "scale: must be in [1, 4096] (got 8192)"));
}

class MalformedWeightsOnGpu : public GpuTest {
 protected:
  // The tiny network with an unused 1x1 conv of `channels` channels on its input, and `sizeMultiple`.
  std::filesystem::path widened(int channels, int sizeMultiple = 4) {
    io::SafetensorsFile file = io::readSafetensors(kTiny);
    nlohmann::json graph = nlohmann::json::parse(file.metadata.at("sixway.graph"));
    graph["size_multiple"] = sizeMultiple;
    const nlohmann::json wide = {
        {"name", "wide"},           {"op", "conv2d"}, {"inputs", {"input"}}, {"in_channels", 4},
        {"out_channels", channels}, {"kernel", 1},    {"stride", 1},         {"scale", 1},
        {"activation", "none"}};
    graph["nodes"].insert(graph["nodes"].begin() + 1, wide);
    file.tensors.push_back(io::Tensor::fromFloat("wide.weight", io::DType::F32, {channels, 4, 1, 1},
                                                 std::vector<float>(size_t(channels) * 4, 0.0f)));
    file.tensors.push_back(
        io::Tensor::fromFloat("wide.bias", io::DType::F32, {channels}, std::vector<float>(channels, 0.0f)));
    file.metadata["sixway.graph"] = graph.dump();
    io::writeSafetensors(dir_ / "net.safetensors", file.tensors, file.metadata);
    return dir_ / "net.safetensors";
  }
  std::string buildError(const std::filesystem::path& weights, uint32_t guide) {
    return inputErrorMessage(
        [&] { nn::Network(context(), pipelineCache(), io::readSafetensors(weights), guide, guide); });
  }

  TempDir dir_;
};

TEST_F(MalformedWeightsOnGpu, NetworkRefusesTheFileBeforeBuildingAnything) {
  TempDir dir;
  io::SafetensorsFile file = io::readSafetensors(kTiny);
  std::erase_if(file.tensors,
                [](const io::Tensor& t) { return t.name == "output.weight" || t.name == "mid.1.beta"; });
  io::writeSafetensors(dir / "net.safetensors", file.tensors, file.metadata);
  EXPECT_THAT(inputErrorMessage([&] {
                nn::Network(context(), pipelineCache(), io::readSafetensors(dir / "net.safetensors"), 32, 32);
              }),
              namesFileAndProblem(dir / "net.safetensors", "missing tensor 'mid.1.beta'"));
}

// A network that reads the albedo is not built without one, and takes none outside [0, 1].
TEST_F(MalformedWeightsOnGpu, AlbedoNetworkNeedsTheAlbedo) {
  const io::SafetensorsFile file =
      io::readSafetensors(std::filesystem::path(SIXWAY_TEST_DATA_DIR) / "nn" / "albedo_input.safetensors");
  try {
    nn::Network(context(), pipelineCache(), file, 16, 16);
    ADD_FAILURE() << "built without an albedo";
  } catch (const gpu::GpuError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("albedo_input.safetensors reads the smoke's albedo"));
  }
  nn::NetworkOptions options;
  options.albedo = 0.9f;
  nn::Network network(context(), pipelineCache(), file, 16, 16, options);
  EXPECT_TRUE(network.readsAlbedo());
  EXPECT_THROW(network.setAlbedo(1.5f), gpu::GpuError);
  EXPECT_THROW(network.setAlbedo(std::numeric_limits<float>::quiet_NaN()), gpu::GpuError);
  EXPECT_FALSE(nn::Network(context(), pipelineCache(), io::readSafetensors(kTiny), 16, 16).readsAlbedo());
}

// A network that the device cannot hold even at the smallest lightmaps is the weights' fault: the line names
// the file and the graph's field, with the size the map needs (it was blamed on render.lightmap_size, with a
// size that had wrapped 32 bits).
TEST_F(MalformedWeightsOnGpu, ANetworkBeyondTheDeviceAtTheSmallestLightmapsBlamesTheGraph) {
  // A 16x16 map: 18 texels a row (slack and border), 18 rows a group of 4 channels, 16 bytes a texel.
  const uint64_t groupBytes = 18 * 18 * 16;
  const uint64_t groups = 2 * (uint64_t(context().limits().maxStorageBufferRange) / groupBytes + 1);
  if (groups > 200000) GTEST_SKIP() << "the device binds maps too large for a small test file";
  const std::filesystem::path weights = widened(int(groups * 4));
  const std::string channels = "sixway.graph.nodes[1].out_channels is " + std::to_string(groups * 4) +
                               ": at 16×16 lightmaps, net.safetensors wide needs a storage buffer of ";
  EXPECT_THAT(buildError(weights, 16), namesFileAndProblem(weights, channels));
  EXPECT_THAT(buildError(weights, 16), ::testing::EndsWith("; reduce it"));
  // A larger guide: built again at 16x16, which does not fit either.
  EXPECT_THAT(buildError(weights, 64), namesFileAndProblem(weights, channels));
}

TEST_F(MalformedWeightsOnGpu, ASizeMultiplePaddingTheGuideBeyondTheDeviceBlamesTheGraph) {
  // At 4096x4096, 64 channels take more than 4 GiB, beyond any device's storage-buffer range.
  const std::filesystem::path weights = widened(64, 4096);
  EXPECT_THAT(buildError(weights, 16),
              namesFileAndProblem(weights,
                                  "sixway.graph.size_multiple is 4096: it pads 16×16 lightmaps to "
                                  "4096×4096, where net.safetensors "));
}

// What fits at the smallest lightmaps but not at these is the lightmaps' fault: a gpu::LimitError, for the
// caller to name its setting (render.lightmap_size).
TEST_F(MalformedWeightsOnGpu, ANetworkBeyondTheDeviceOnlyAtLargeLightmapsIsALimitError) {
  try {
    nn::Network(context(), pipelineCache(), io::readSafetensors(kTiny), 16384, 16384);
    ADD_FAILURE() << "a 16384x16384 network was built";
  } catch (const gpu::LimitError& e) {
    EXPECT_THAT(e.problem(), ::testing::HasSubstr("tiny.safetensors input needs"));
  }
}

}  // namespace
}  // namespace sixway::test
