// The engine's two smoke instances through sixway's C++ API (include/sixway/*.h).
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <cstdio>
#include <memory>

#include "smoke_instances.h"

namespace {

class CppInstances : public SmokeInstances {
 public:
  explicit CppInstances(const SmokeSetup& s)
      : device_(engineDevice(s)),
        simulationA_(device_, s.scene),
        simulationB_(device_, s.scene),
        rendererA_(rendererA(device_, simulationA_, s)),
        rendererB_(device_, simulationB_, {.shareNetwork = rendererA_.get()},
                   sixway::RenderingFormats{{s.colorFormat}, s.depthFormat}),
        depthFormat_(s.depthFormat),
        colorFormat_(s.colorFormat) {
    simulationB_.setPlacement(s.placementB);
    const sixway::Light sun{.direction = s.sunDirection, .color = s.sunIrradiance, .intensity = 1.0f};
    rendererA_->setLights({sun});
    rendererB_.setLights({sun});
  }

  void setCamera(const glm::mat4& view, const glm::mat4& projection) override {
    rendererA_->setViewProjection(view, projection);
    rendererB_.setViewProjection(view, projection);
  }
  void setWorld(const EngineEmitter& e, const std::vector<EngineObstacle>& obstacles,
                double seconds) override {
    simulationA_.setEmitters({{e.position, e.radius, e.velocity, e.densityRate, e.temperatureRate, e.on}});
    std::vector<sixway::Obstacle> list;
    for (const EngineObstacle& o : obstacles)
      list.push_back({sixway::Obstacle::Shape(o.shape), o.position, o.radius, o.size, o.height, o.axis});
    simulationA_.setObstacles(list, seconds);
  }
  void recordSimulations(VkCommandBuffer commands, uint64_t frame, double seconds) override {
    simulationA_.record(commands, frame, seconds);
    simulationB_.record(commands, frame, seconds);
  }
  void recordLightmapsB(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    rendererB_.recordLightmaps(commands, frame,
                               {i.depth, i.depthView, depthFormat_,
                                VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, i.width, i.height});
  }
  void recordA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    rendererA_->record(commands, frame,
                       {{i.color, i.colorView, colorFormat_, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                        {i.depth, i.depthView, depthFormat_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                         VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
                        i.width,
                        i.height,
                        {}});
    recorded_ = true;
  }
  void recordLightmapsA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    rendererA_->recordLightmaps(commands, frame,
                                {i.depth, i.depthView, depthFormat_,
                                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, i.width, i.height});
    recorded_ = true;
  }
  PackedLightmaps lightmapsA() const override {
    const sixway::LightmapTextures maps = rendererA_->lightmaps();
    return {maps.viewA, maps.viewB, {maps.corners[0], maps.corners[1], maps.corners[2], maps.corners[3]}};
  }
  void recordCompositeB(VkCommandBuffer commands) override { rendererB_.recordComposite(commands); }
  void forgetTargets() override { rendererA_->forgetTargets(); }
  glm::vec3 middle(int instance) const override {
    if (!recorded_) return glm::vec3((instance == 0 ? simulationA_ : simulationB_).placement()[3]);
    const sixway::LightmapTextures maps = (instance == 0 ? *rendererA_ : rendererB_).lightmaps();
    return 0.25f * (maps.corners[0] + maps.corners[1] + maps.corners[2] + maps.corners[3]);
  }
  uint64_t hostWaits() const override { return device_.hostWaits(); }
  std::vector<std::pair<std::string, double>> stageTimes() const override {
    std::vector<std::pair<std::string, double>> times;
    for (const auto& t : simulationA_.stageTimes()) times.emplace_back(t.name, t.milliseconds);
    for (const sixway::SmokeRenderer* r :
         {static_cast<const sixway::SmokeRenderer*>(rendererA_.get()), &rendererB_})
      for (const auto& t : r->stageTimes()) times.emplace_back(t.name, t.milliseconds);
    return times;
  }

 private:
  // A into the engine's images, or for its own material: inside its rendering, lightmaps in RLT/BBF.
  static std::unique_ptr<sixway::SmokeRenderer> rendererA(sixway::Device& device,
                                                          sixway::SmokeSimulation& simulation,
                                                          const SmokeSetup& s) {
    if (!s.ownMaterialA)
      return std::make_unique<sixway::SmokeRenderer>(
          device, simulation, sixway::RendererOptions{.weights = s.weights}, s.colorFormat);
    return std::make_unique<sixway::SmokeRenderer>(
        device, simulation,
        sixway::RendererOptions{.weights = s.weights, .packing = sixway::LightmapPacking::RltBbf},
        sixway::RenderingFormats{{s.colorFormat}, s.depthFormat});
  }
  static sixway::Device engineDevice(const SmokeSetup& s) {
    sixway::EngineDevice description{s.instance, s.physicalDevice, s.device,
                                     s.queue,    s.queueFamily,    s.extensions,
                                     s.features, s.framesInFlight, s.submitAndWait};
    description.allocator = s.allocator;
    description.pipelineCache = s.pipelineCache;
    description.getInstanceProcAddr = s.getInstanceProcAddr;
    description.log = [](const std::string& line) { std::printf("sixway note: %s\n", line.c_str()); };
    return sixway::Device(description);
  }

  sixway::Device device_;
  sixway::SmokeSimulation simulationA_, simulationB_;
  std::unique_ptr<sixway::SmokeRenderer> rendererA_;
  sixway::SmokeRenderer rendererB_;
  VkFormat depthFormat_, colorFormat_;
  bool recorded_ = false;
};

}  // namespace

std::unique_ptr<SmokeInstances> cppInstances(const SmokeSetup& setup) {
  return std::make_unique<CppInstances>(setup);
}
