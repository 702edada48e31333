// The engine's targets passed per record() (FrameTargets): images in the engine's own layouts, moved by
// sixway to GENERAL and on to the layouts asked for; a target of another size, a viewport inside a larger
// target, and an engine that alternates between two targets frame by frame, each against the same frames
// recorded into one fixed target; the same through the C API; targets that do not fit refused before anything
// is recorded.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/sixway.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/image.h"
#include "runtime/engine_harness.h"
#include "scene/scene.h"
#include "support/engine_projections.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

constexpr int kFrames = 4;
const float kBackground[4] = {0.1f, 0.2f, 0.3f, 1.0f};

// Colour and depth in GENERAL, as FrameTargets, with a viewport (zero: the whole image).
FrameTargets generalTargets(const EngineTargets& t, VkRect2D viewport = {}) {
  FrameTargets targets;
  targets.color = {t.color.handle(), t.color.view(), t.color.desc().format};
  targets.depth = {t.depth.handle(), t.depth.view(), t.depth.desc().format};
  targets.width = t.color.desc().width;
  targets.height = t.color.desc().height;
  targets.viewport = viewport;
  return targets;
}

// The pixels of `image` (RGBA, `width` wide) inside `rect`, row by row.
std::vector<float> crop(const std::vector<float>& image, uint32_t width, VkRect2D rect) {
  std::vector<float> inside;
  for (uint32_t y = 0; y < rect.extent.height; ++y) {
    const size_t row = (size_t(rect.offset.y) + y) * width + uint32_t(rect.offset.x);
    inside.insert(inside.end(), image.begin() + ptrdiff_t(row * 4),
                  image.begin() + ptrdiff_t((row + rect.extent.width) * 4));
  }
  return inside;
}

class EngineTargetsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene = sceneWithoutObstacles(dir.path());
    const scene::Scene parsed = scene::loadScene(scene);
    frameSeconds = parsed.time.frameDt;
    width = uint32_t(parsed.render.width);
    height = uint32_t(parsed.render.height);
    // Frames 0..kFrames − 1 into one fixed target in GENERAL: what every variant must give.
    EngineTargets fixed(engine.context, width, height);
    SmokeSimulation simulation(engine.device, scene);
    SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, fixed.target());
    renderer.setCamera(sceneCamera());
    for (uint64_t frame = 0; frame < kFrames; ++frame) {
      VkCommandBuffer commands = engine.begin();
      fixed.recordClear(commands, kBackground);
      simulation.record(commands, frame);
      renderer.record(commands, frame);
      engine.submitAndWait();
      expected.push_back(fixed.colorPixels());
    }
    ASSERT_GT(*std::max_element(expected.back().begin(), expected.back().end()), 0.2f) << "no smoke";
  }

  TempDir dir;
  std::filesystem::path scene;
  Device own{{.validate = true}};
  BorrowingEngine engine{own};
  uint32_t width = 0, height = 0;
  double frameSeconds = 0.0;                 // the scene's time.frame_dt
  std::vector<std::vector<float>> expected;  // per frame
};

// The engine keeps its colour in COLOR_ATTACHMENT_OPTIMAL and wants it back in TRANSFER_SRC_OPTIMAL (it
// copies it on); its depth in DEPTH_STENCIL_READ_ONLY_OPTIMAL, wanted back as an attachment.
// Validation checks every layout each command sees.
TEST_F(EngineTargetsTest, OptimalLayoutsAreMovedAsAskedAndGiveTheSameSmoke) {
  EngineTargets targets(engine.context, width, height);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.color.desc().format);
  renderer.setCamera(sceneCamera());
  FrameTargets frameTargets = generalTargets(targets);
  frameTargets.color.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  frameTargets.color.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  frameTargets.depth.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  frameTargets.depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  for (uint64_t frame = 0; frame < kFrames; ++frame) {
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, kBackground);  // in GENERAL, then into the engine's layouts
    const VkImage color = targets.color.handle(), depth = targets.depth.handle();
    const VkFormat colorFormat = targets.color.desc().format, depthFormat = targets.depth.desc().format;
    gpu::recordLayoutChange(commands, color, colorFormat, VK_IMAGE_LAYOUT_GENERAL, frameTargets.color.layout);
    gpu::recordLayoutChange(commands, depth, depthFormat, VK_IMAGE_LAYOUT_GENERAL, frameTargets.depth.layout);
    simulation.record(commands, frame);
    renderer.record(commands, frame, frameTargets);
    gpu::recordLayoutChange(commands, color, colorFormat, frameTargets.color.finalLayout,
                            VK_IMAGE_LAYOUT_GENERAL);
    gpu::recordLayoutChange(commands, depth, depthFormat, frameTargets.depth.finalLayout,
                            VK_IMAGE_LAYOUT_GENERAL);
    engine.submitAndWait();
    EXPECT_EQ(maxDifference(targets.colorPixels(), expected[frame]), 0.0) << "frame " << frame;
  }
  EXPECT_EQ(own.validationMessages(), 0u);
}

// Frame by frame the engine alternates between its full-size target and a larger one whose viewport holds
// the camera's image (dynamic resolution, split screen): the smoke inside the viewport is the fixed target's,
// nothing outside it is touched, and the host never waits.
TEST_F(EngineTargetsTest, AnotherSizeAndAViewportGiveTheSameCameraImage) {
  EngineTargets full(engine.context, width, height);
  EngineTargets larger(engine.context, width + 40, height + 24);
  const VkRect2D viewport{{16, 8}, {width, height}};
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, full.color.desc().format);
  renderer.setCamera(sceneCamera());
  uint64_t waitsAfterFirstTwo = 0;
  for (uint64_t frame = 0; frame < kFrames; ++frame) {
    const bool inLarger = frame % 2 == 1;
    const EngineTargets& targets = inLarger ? larger : full;
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, kBackground);
    simulation.record(commands, frame);
    renderer.record(commands, frame, generalTargets(targets, inLarger ? viewport : VkRect2D{}));
    if (frame == 1) waitsAfterFirstTwo = engine.device.hostWaits();
    engine.submitAndWait();
    EXPECT_EQ(renderer.width(), width);
    const std::vector<float> image = targets.colorPixels();
    if (!inLarger) {
      EXPECT_EQ(maxDifference(image, expected[frame]), 0.0) << "frame " << frame;
      continue;
    }
    EXPECT_LT(maxDifference(crop(image, width + 40, viewport), expected[frame]), 1e-6) << "frame " << frame;
    // Outside the viewport: the clear colour, as the fixed target's corner holds it (no smoke there).
    size_t outside = 0, touched = 0;
    for (uint32_t y = 0; y < height + 24; ++y)
      for (uint32_t x = 0; x < width + 40; ++x) {
        if (x >= 16 && x < 16 + width && y >= 8 && y < 8 + height) continue;
        ++outside;
        for (int c = 0; c < 4; ++c)
          if (image[(size_t(y) * (width + 40) + x) * 4 + c] != expected[0][c]) {
            ++touched;
            break;
          }
      }
    EXPECT_GT(outside, 0u);
    EXPECT_EQ(touched, 0u) << "pixels outside the viewport were drawn";
  }
  EXPECT_EQ(engine.device.hostWaits(), waitsAfterFirstTwo) << "sixway blocked the host after the first two";
  EXPECT_EQ(own.validationMessages(), 0u);
}

// sixwayCreateRendererForFormat, sixwaySimulationRecordSeconds and sixwayRendererRecordTargets on the
// engine's device: the same frames.
TEST_F(EngineTargetsTest, TheCApiTakesTheSameTargets) {
  const gpu::Context& context = engine.context;
  const std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
  const SixwayEngineDevice description{context.instance(),
                                       context.physicalDevice(),
                                       context.device(),
                                       context.queue(),
                                       context.queueFamily(),
                                       extensions.data(),
                                       uint32_t(extensions.size()),
                                       engine.features.chain(),
                                       2,
                                       nullptr,
                                       nullptr};
  SixwayDevice device = nullptr;
  ASSERT_EQ(sixwayCreateEngineDevice(&description, &device), SIXWAY_SUCCESS) << sixwayLastError();
  SixwaySimulation simulation = nullptr;
  ASSERT_EQ(sixwayCreateSimulation(device, scene.c_str(), &simulation), SIXWAY_SUCCESS) << sixwayLastError();
  EngineTargets targets(context, width, height);
  SixwayRenderer renderer = nullptr;
  ASSERT_EQ(sixwayCreateRendererForFormat(device, simulation, kWeights.c_str(), targets.color.desc().format,
                                          &renderer),
            SIXWAY_SUCCESS)
      << sixwayLastError();
  const Camera camera = sceneCamera();
  const glm::mat4 view = glm::lookAtRH(camera.position, camera.target, camera.up);
  const glm::mat4 projection = engineProjection(DepthConvention::Standard, glm::radians(camera.fovYDegrees),
                                                float(width) / float(height), camera.near, camera.far);
  ASSERT_EQ(sixwayRendererSetViewProjection(renderer, &view[0][0], &projection[0][0]), SIXWAY_SUCCESS);
  const FrameTargets t = generalTargets(targets);
  const SixwayFrameTargets frameTargets{
      {t.color.image, t.color.view, t.color.format, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL},
      {t.depth.image, t.depth.view, t.depth.format, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL},
      width,
      height,
      {}};
  for (uint64_t frame = 0; frame < kFrames; ++frame) {
    VkCommandBuffer commands = engine.begin();
    targets.recordClear(commands, kBackground);
    uint32_t steps = 0;  // one scene frame of time: the scene's steps, as the fixed target's frames had
    ASSERT_EQ(sixwaySimulationRecordSeconds(simulation, commands, frame, frameSeconds, &steps),
              SIXWAY_SUCCESS)
        << sixwayLastError();
    EXPECT_GT(steps, 0u);
    ASSERT_EQ(sixwayRendererRecordTargets(renderer, commands, frame, &frameTargets), SIXWAY_SUCCESS)
        << sixwayLastError();
    engine.submitAndWait();
    EXPECT_LT(maxDifference(targets.colorPixels(), expected[frame]), 1e-3) << "frame " << frame;
  }
  SixwayFrameTargets undefined = frameTargets;
  undefined.depth.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkCommandBuffer commands = engine.begin();
  EXPECT_EQ(sixwayRendererRecordTargets(renderer, commands, kFrames, &undefined),
            SIXWAY_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sixwayLastError()).find("UNDEFINED"), std::string::npos) << sixwayLastError();
  EXPECT_EQ(sixwayRendererRecordTargets(renderer, commands, kFrames, nullptr), SIXWAY_ERROR_INVALID_ARGUMENT);
  engine.submitAndWait();
  sixwayDestroyRenderer(renderer);
  sixwayDestroySimulation(simulation);
  sixwayDestroyDevice(device);
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST_F(EngineTargetsTest, TargetsThatDoNotFitAreRefusedBeforeAnythingIsRecorded) {
  EngineTargets targets(engine.context, width, height);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.color.desc().format);
  renderer.setCamera(sceneCamera());
  VkCommandBuffer commands = engine.begin();
  EXPECT_THROW(renderer.record(commands, 0), std::invalid_argument) << "no targets passed";
  FrameTargets undefined = generalTargets(targets);
  undefined.color.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  EXPECT_THROW(renderer.record(commands, 0, undefined), std::invalid_argument);
  FrameTargets otherFormat = generalTargets(targets);
  otherFormat.color.format = VK_FORMAT_R8G8B8A8_UNORM;
  EXPECT_THROW(renderer.record(commands, 0, otherFormat), std::invalid_argument);
  EXPECT_THROW(renderer.record(commands, 0, generalTargets(targets, {{8, 0}, {width, height}})),
               std::invalid_argument)
      << "a viewport beyond the image";
  FrameTargets colorDepth = generalTargets(targets);
  colorDepth.depth = colorDepth.color;
  EXPECT_THROW(renderer.record(commands, 0, colorDepth), std::invalid_argument) << "a colour image as depth";
  EngineTargets stencil(engine.context, width, height, VK_FORMAT_D24_UNORM_S8_UINT);
  FrameTargets depthOnly = generalTargets(stencil);
  depthOnly.depth.layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  EXPECT_THROW(renderer.record(commands, 0, depthOnly), std::invalid_argument)
      << "a depth-only layout for a depth image with stencil";
  FrameTargets corner = generalTargets(targets, {{4, 4}, {0, 0}});
  EXPECT_THROW(renderer.record(commands, 0, corner), std::invalid_argument)
      << "an empty viewport off the corner";
  engine.submitAndWait();  // nothing was recorded into it
  EXPECT_EQ(own.validationMessages(), 0u);
}

// The engine's own dynamic rendering: colour attachment 0 its frame, attachment 1 a second target (e.g. its
// motion vectors) that sixway must leave alone, its depth buffer read-only as the depth attachment and
// sampled by sixway. The composite is recorded into the primary command buffer, or into a secondary one
// recorded for that rendering.
void recordInsideRendering(VkCommandBuffer commands, VkCommandBuffer secondary, const EngineTargets& targets,
                           const gpu::Image& second, const RenderingFormats& formats,
                           const SmokeRenderer& renderer) {
  const VkExtent2D size{targets.color.desc().width, targets.color.desc().height};
  auto colorAttachment = [](const gpu::Image& image) {
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = image.view();
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    return a;
  };
  const VkRenderingAttachmentInfo colors[2] = {colorAttachment(targets.color), colorAttachment(second)};
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = targets.depth.view();
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, size};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 2;
  rendering.pColorAttachments = colors;
  rendering.pDepthAttachment = &depth;
  if (!secondary) {
    vkCmdBeginRendering(commands, &rendering);
    renderer.recordComposite(commands);
    vkCmdEndRendering(commands);
    return;
  }
  VkCommandBufferInheritanceRenderingInfo inheritedRendering{
      VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_RENDERING_INFO};
  inheritedRendering.colorAttachmentCount = uint32_t(formats.colors.size());
  inheritedRendering.pColorAttachmentFormats = formats.colors.data();
  inheritedRendering.depthAttachmentFormat = formats.depth;
  inheritedRendering.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkCommandBufferInheritanceInfo inheritance{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO,
                                             &inheritedRendering};
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_RENDER_PASS_CONTINUE_BIT;
  begin.pInheritanceInfo = &inheritance;
  SIXWAY_VK(vkResetCommandBuffer(secondary, 0));
  SIXWAY_VK(vkBeginCommandBuffer(secondary, &begin));
  renderer.recordComposite(secondary);
  SIXWAY_VK(vkEndCommandBuffer(secondary));
  rendering.flags = VK_RENDERING_CONTENTS_SECONDARY_COMMAND_BUFFERS_BIT;
  vkCmdBeginRendering(commands, &rendering);
  vkCmdExecuteCommands(commands, 1, &secondary);
  vkCmdEndRendering(commands);
}

TEST_F(EngineTargetsTest, InsideTheEnginesOwnRenderingTheSameSmoke) {
  VkCommandBuffer secondary = VK_NULL_HANDLE;
  const VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr,
                                             engine.frame.pool, VK_COMMAND_BUFFER_LEVEL_SECONDARY, 1};
  SIXWAY_VK(vkAllocateCommandBuffers(engine.context.device(), &allocate, &secondary));
  const RenderingFormats formats{{VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM},
                                 VK_FORMAT_D32_SFLOAT};
  for (bool inSecondary : {false, true}) {
    EngineTargets targets(engine.context, width, height);
    gpu::Image second(engine.context, {width, height, 1, VK_FORMAT_R8G8B8A8_UNORM,
                                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                           VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                       "engine motion vectors"});
    SmokeSimulation simulation(engine.device, scene);
    SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, formats);
    renderer.setCamera(sceneCamera());
    const CompositeTargets composite{targets.depth.handle(),
                                     targets.depth.view(),
                                     VK_FORMAT_D32_SFLOAT,
                                     VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                                     width,
                                     height};
    for (uint64_t frame = 0; frame < kFrames; ++frame) {
      VkCommandBuffer commands = engine.begin();
      targets.recordClear(commands, kBackground);
      const VkClearColorValue motion{{0.25f, 0.5f, 0.75f, 1.0f}};
      const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(commands, second.handle(), VK_IMAGE_LAYOUT_GENERAL, &motion, 1, &all);
      const VkImage color = targets.color.handle(), depth = targets.depth.handle();
      const VkImageLayout colorOptimal = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          depthReadOnly = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
      gpu::recordLayoutChange(commands, color, formats.colors[0], VK_IMAGE_LAYOUT_GENERAL, colorOptimal);
      gpu::recordLayoutChange(commands, second.handle(), formats.colors[1], VK_IMAGE_LAYOUT_GENERAL,
                              colorOptimal);
      gpu::recordLayoutChange(commands, depth, formats.depth, VK_IMAGE_LAYOUT_GENERAL, depthReadOnly);
      simulation.record(commands, frame);
      renderer.recordLightmaps(commands, frame, composite);
      recordInsideRendering(commands, inSecondary ? secondary : VK_NULL_HANDLE, targets, second, formats,
                            renderer);
      gpu::recordLayoutChange(commands, color, formats.colors[0], colorOptimal, VK_IMAGE_LAYOUT_GENERAL);
      gpu::recordLayoutChange(commands, second.handle(), formats.colors[1], colorOptimal,
                              VK_IMAGE_LAYOUT_GENERAL);
      gpu::recordLayoutChange(commands, depth, formats.depth, depthReadOnly, VK_IMAGE_LAYOUT_GENERAL);
      engine.submitAndWait();
      EXPECT_EQ(maxDifference(targets.colorPixels(), expected[frame]), 0.0)
          << "frame " << frame << (inSecondary ? ", secondary" : ", primary");
    }
    for (uint32_t texel : second.download<uint32_t>())
      ASSERT_EQ(texel, 0xffbf8040u) << "sixway wrote into the engine's second attachment";
    // The composite's GPU time, measured inside the engine's rendering, arrives with the frame's others.
    const std::vector<StageTime> times = renderer.stageTimes();
    const auto shade =
        std::find_if(times.begin(), times.end(), [](const StageTime& t) { return t.name == "shade"; });
    ASSERT_NE(shade, times.end());
    EXPECT_GT(shade->milliseconds, 0.0);
  }
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST_F(EngineTargetsTest, InsideTheEnginesRenderingMisuseIsRefused) {
  EngineTargets targets(engine.context, width, height);
  SmokeSimulation simulation(engine.device, scene);
  SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights},
                         RenderingFormats{{VK_FORMAT_R16G16B16A16_SFLOAT}, VK_FORMAT_D32_SFLOAT});
  VkCommandBuffer commands = engine.begin();
  CompositeTargets composite{targets.depth.handle(),
                             targets.depth.view(),
                             VK_FORMAT_D32_SFLOAT,
                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                             width,
                             height};
  EXPECT_THROW(renderer.recordLightmaps(commands, 0, composite), std::invalid_argument) << "no camera yet";
  renderer.setCamera(sceneCamera());
  EXPECT_THROW(renderer.recordComposite(commands), std::invalid_argument) << "before recordLightmaps";
  EXPECT_THROW(renderer.record(commands, 0, generalTargets(targets)), std::invalid_argument);
  CompositeTargets writable = composite;
  writable.depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  EXPECT_THROW(renderer.recordLightmaps(commands, 0, writable), std::invalid_argument);
  CompositeTargets empty = composite;
  empty.width = 0;
  EXPECT_THROW(renderer.recordLightmaps(commands, 0, empty), std::invalid_argument);
  CompositeTargets outside = composite;
  outside.viewport = {{int32_t(width / 2), 0}, {width, height}};
  EXPECT_THROW(renderer.recordLightmaps(commands, 0, outside), std::invalid_argument);
  SmokeRenderer images(engine.device, simulation, {.weights = kWeights}, VK_FORMAT_R16G16B16A16_SFLOAT);
  images.setCamera(sceneCamera());
  EXPECT_THROW(images.recordLightmaps(commands, 0, composite), std::invalid_argument);
  EXPECT_THROW(SmokeRenderer(engine.device, simulation, {.weights = kWeights}, RenderingFormats{}),
               std::invalid_argument)
      << "no colour attachment";
  engine.submitAndWait();  // nothing was recorded into it
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
