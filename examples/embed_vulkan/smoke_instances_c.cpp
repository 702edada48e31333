// The engine's two smoke instances through sixway's C API (include/sixway/sixway.h): handles, result codes
// and the last error's message, as a C engine or another language's binding would use them.
#include <sixway/sixway.h>

#include <cstdio>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>

#include "smoke_instances.h"

namespace {

// A failed call's one-line message as the example's error.
void check(SixwayResult result) {
  if (result != SIXWAY_SUCCESS) throw std::runtime_error(sixwayLastError());
}

class CApiInstances : public SmokeInstances {
 public:
  explicit CApiInstances(const SmokeSetup& s)
      : submitAndWait_(s.submitAndWait), colorFormat_(s.colorFormat), depthFormat_(s.depthFormat) {
    std::vector<const char*> extensions;
    for (const std::string& e : s.extensions) extensions.push_back(e.c_str());
    SixwayEngineDevice engine{};
    engine.instance = s.instance;
    engine.physicalDevice = s.physicalDevice;
    engine.device = s.device;
    engine.queue = s.queue;
    engine.queueFamily = s.queueFamily;
    engine.enabledExtensions = extensions.data();
    engine.enabledExtensionCount = uint32_t(extensions.size());
    engine.enabledFeatures = s.features;
    engine.framesInFlight = s.framesInFlight;
    engine.submitAndWait = [](void* user, void (*record)(void*, VkCommandBuffer), void* context) {
      static_cast<CApiInstances*>(user)->submitAndWait_(
          [&](VkCommandBuffer commands) { record(context, commands); });
    };
    engine.submitUser = this;
    engine.allocator = s.allocator;
    engine.pipelineCache = s.pipelineCache;
    engine.getInstanceProcAddr = s.getInstanceProcAddr;
    engine.log = [](void*, const char* line) { std::printf("sixway note: %s\n", line); };
    try {
      check(sixwayCreateEngineDevice(&engine, &device_));
      check(sixwayCreateSimulation(device_, s.scene.c_str(), &simulations_[0]));
      check(sixwayCreateSimulation(device_, s.scene.c_str(), &simulations_[1]));
      check(sixwaySimulationSetPlacement(simulations_[1], glm::value_ptr(s.placementB)));
      SixwayRendererInfo a{};
      a.weightsPath = s.weights.c_str();
      a.colorFormat = s.colorFormat;
      if (s.ownMaterialA) {  // for the engine's material: inside its rendering, lightmaps in RLT/BBF
        a.renderingColors = &s.colorFormat;
        a.renderingColorCount = 1;
        a.renderingDepth = s.depthFormat;
        a.lightmapPacking = 1;
      }
      check(sixwayCreateRendererFromInfo(device_, simulations_[0], &a, &renderers_[0]));
      SixwayRendererInfo b{};
      b.shareNetwork = renderers_[0];
      b.renderingColors = &s.colorFormat;
      b.renderingColorCount = 1;
      b.renderingDepth = s.depthFormat;
      check(sixwayCreateRendererFromInfo(device_, simulations_[1], &b, &renderers_[1]));
      const SixwayLight sun{0,
                            {s.sunDirection.x, s.sunDirection.y, s.sunDirection.z},
                            {0.0f, 0.0f, 0.0f},
                            {s.sunIrradiance.r, s.sunIrradiance.g, s.sunIrradiance.b},
                            1.0f,
                            1};
      for (SixwayRenderer r : renderers_) check(sixwayRendererSetLights(r, &sun, 1));
      for (int i = 0; i < 2; ++i) placements_[i] = glm::vec3(i == 0 ? glm::mat4(1.0f)[3] : s.placementB[3]);
    } catch (...) {
      release();
      throw;
    }
  }
  ~CApiInstances() override { release(); }

  void setCamera(const glm::mat4& view, const glm::mat4& projection) override {
    for (SixwayRenderer r : renderers_)
      check(sixwayRendererSetViewProjection(r, glm::value_ptr(view), glm::value_ptr(projection)));
  }
  void setWorld(const EngineEmitter& e, const std::vector<EngineObstacle>& obstacles,
                double seconds) override {
    const SixwayEmitter emitter{{e.position.x, e.position.y, e.position.z},
                                e.radius,
                                {e.velocity.x, e.velocity.y, e.velocity.z},
                                e.densityRate,
                                e.temperatureRate,
                                e.on ? 1 : 0};
    check(sixwaySimulationSetEmitters(simulations_[0], &emitter, 1));
    std::vector<SixwayObstacle> list;
    for (const EngineObstacle& o : obstacles)
      list.push_back({SixwayObstacleShape(o.shape),
                      {o.position.x, o.position.y, o.position.z},
                      o.radius,
                      {o.size.x, o.size.y, o.size.z},
                      o.height,
                      {o.axis.x, o.axis.y, o.axis.z},
                      1});
    check(sixwaySimulationSetObstacles(simulations_[0], list.data(), uint32_t(list.size()), seconds));
  }
  void recordSimulations(VkCommandBuffer commands, uint64_t frame, double seconds) override {
    for (SixwaySimulation s : simulations_)
      check(sixwaySimulationRecordSeconds(s, commands, frame, seconds, nullptr));
  }
  void recordLightmapsB(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    const SixwayCompositeTargets targets{
        i.depth,  i.depthView, depthFormat_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, i.width,
        i.height, {}};
    check(sixwayRendererRecordLightmaps(renderers_[1], commands, frame, &targets));
  }
  void recordA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    const VkImageLayout color = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        depth = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    SixwayFrameTargets targets{};
    targets.color = {i.color, i.colorView, colorFormat_, color, color};
    targets.depth = {i.depth, i.depthView, depthFormat_, depth, depth};
    targets.width = i.width;
    targets.height = i.height;
    check(sixwayRendererRecordTargets(renderers_[0], commands, frame, &targets));
    recorded_ = true;
  }
  void recordLightmapsA(VkCommandBuffer commands, uint64_t frame, const FrameImagesView& i) override {
    const SixwayCompositeTargets targets{
        i.depth,  i.depthView, depthFormat_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, i.width,
        i.height, {}};
    check(sixwayRendererRecordLightmaps(renderers_[0], commands, frame, &targets));
    recorded_ = true;
  }
  PackedLightmaps lightmapsA() const override {
    SixwayLightmapTextures maps;
    check(sixwayRendererLightmaps(renderers_[0], &maps));
    PackedLightmaps packed{maps.viewA, maps.viewB, {}};
    for (int c = 0; c < 4; ++c) packed.corners[c] = glm::make_vec3(maps.corners[c]);
    return packed;
  }
  void recordCompositeB(VkCommandBuffer commands) override {
    check(sixwayRendererRecordComposite(renderers_[1], commands));
  }
  void forgetTargets() override { check(sixwayRendererForgetTargets(renderers_[0])); }
  glm::vec3 middle(int instance) const override {
    if (!recorded_) return placements_[instance];
    SixwayLightmapTextures maps;
    check(sixwayRendererLightmaps(renderers_[instance], &maps));
    glm::vec3 sum(0.0f);
    for (const auto& corner : maps.corners) sum += glm::make_vec3(corner);
    return 0.25f * sum;
  }
  uint64_t hostWaits() const override {
    uint64_t waits = 0;
    check(sixwayDeviceHostWaits(device_, &waits));
    return waits;
  }
  std::vector<std::pair<std::string, double>> stageTimes() const override { return {}; }

 private:
  void release() {
    for (SixwayRenderer& r : renderers_) sixwayDestroyRenderer(r), r = nullptr;
    for (SixwaySimulation& s : simulations_) sixwayDestroySimulation(s), s = nullptr;
    sixwayDestroyDevice(device_);
    device_ = nullptr;
  }

  std::function<void(const std::function<void(VkCommandBuffer)>&)> submitAndWait_;
  VkFormat colorFormat_, depthFormat_;
  SixwayDevice device_ = nullptr;
  SixwaySimulation simulations_[2] = {nullptr, nullptr};
  SixwayRenderer renderers_[2] = {nullptr, nullptr};
  glm::vec3 placements_[2];
  bool recorded_ = false;
};

}  // namespace

std::unique_ptr<SmokeInstances> cApiInstances(const SmokeSetup& setup) {
  return std::make_unique<CApiInstances>(setup);
}
