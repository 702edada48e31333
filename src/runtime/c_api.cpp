// include/sixway/sixway.h over the C++ API: every call that can fail catches what the C++ call throws, keeps
// its message for sixwayLastError() on this thread and returns the matching code.
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/sixway.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <functional>
#include <glm/gtc/type_ptr.hpp>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

struct SixwayDevice_T {
  sixway::Device device;
};
struct SixwaySimulation_T {
  sixway::SmokeSimulation simulation;
};
struct SixwayRenderer_T {
  sixway::SmokeRenderer renderer;
};

namespace {

thread_local std::string lastError;

// Keeps the message, its parts joined, as the thread's last error; nothing escapes (no memory: no message).
template <typename... Parts>
SixwayResult fail(SixwayResult result, const char* message, Parts... more) {
  try {
    lastError.assign(message);
    (lastError.append(more), ...);
  } catch (...) {
    lastError.clear();  // no memory for the message: the code says enough
  }
  return result;
}

// Runs `call`, translating what it throws.
template <typename Call>
SixwayResult guarded(Call&& call) {
  try {
    call();
    return SIXWAY_SUCCESS;
  } catch (const sixway::Error& e) {
    return fail(SIXWAY_ERROR, e.what());
  } catch (const std::invalid_argument& e) {
    return fail(SIXWAY_ERROR_INVALID_ARGUMENT, e.what());
  } catch (const std::bad_alloc&) {
    return fail(SIXWAY_ERROR_OUT_OF_MEMORY, "out of host memory");
  } catch (const std::exception& e) {
    return fail(SIXWAY_ERROR_UNEXPECTED, e.what());
  } catch (...) {
    return fail(SIXWAY_ERROR_UNEXPECTED, "an unknown exception");
  }
}

// EngineDevice::submitAndWait through the C callback: what the recording throws is carried across the
// engine's C frames and thrown again on this side.
struct Recording {
  const std::function<void(VkCommandBuffer)>* record;
  std::exception_ptr failure;
};

void recordTrampoline(void* context, VkCommandBuffer commands) {
  auto* recording = static_cast<Recording*>(context);
  try {
    (*recording->record)(commands);
  } catch (...) {
    recording->failure = std::current_exception();
  }
}

SixwayResult nullArgument(const char* call, const char* what) {
  return fail(SIXWAY_ERROR_INVALID_ARGUMENT, call, ": ", what, " is null");
}

}  // namespace

extern "C" {

const char* sixwayLastError(void) {
  return lastError.c_str();
}

void sixwayVersion(uint32_t* major, uint32_t* minor, uint32_t* patch) {
  const sixway::Version v = sixway::version();
  if (major) *major = v.major;
  if (minor) *minor = v.minor;
  if (patch) *patch = v.patch;
}

SixwayResult sixwayCreateOwnDevice(int validate, SixwayDevice* device) {
  if (!device) return nullArgument("sixwayCreateOwnDevice", "device");
  *device = nullptr;
  return guarded([&] {
    *device = new SixwayDevice_T{sixway::Device(sixway::DeviceOptions{.validate = validate != 0})};
  });
}

SixwayResult sixwayCreateEngineDevice(const SixwayEngineDevice* engine, SixwayDevice* device) {
  if (!engine || !device) return nullArgument("sixwayCreateEngineDevice", engine ? "device" : "engine");
  *device = nullptr;
  return guarded([&] {
    if (engine->enabledExtensionCount > 0 && !engine->enabledExtensions)
      throw std::invalid_argument("sixwayCreateEngineDevice: enabledExtensions is null");
    sixway::EngineDevice e{engine->instance,        engine->physicalDevice, engine->device,
                           engine->queue,           engine->queueFamily,    {},
                           engine->enabledFeatures, engine->framesInFlight};
    e.allocator = engine->allocator;
    e.pipelineCache = engine->pipelineCache;
    e.getInstanceProcAddr = engine->getInstanceProcAddr;
    if (bool(engine->allocateMemory) != bool(engine->freeMemory))
      throw std::invalid_argument("sixwayCreateEngineDevice: allocateMemory and freeMemory go together");
    if (engine->allocateMemory) {
      e.memory.allocate = [allocate = engine->allocateMemory, user = engine->memoryUser](
                              const VkMemoryRequirements& requirements, uint32_t type, bool map) {
        const SixwayMemoryBlock b = allocate(user, &requirements, type, map ? 1 : 0);
        return sixway::MemoryBlock{b.memory, b.offset, b.mapped, b.token};
      };
      e.memory.free = [free = engine->freeMemory, user = engine->memoryUser](const sixway::MemoryBlock& b) {
        const SixwayMemoryBlock block{b.memory, b.offset, b.mapped, b.token};
        free(user, &block);
      };
    }
    if (engine->log)
      e.log = [log = engine->log, user = engine->logUser](const std::string& line) {
        log(user, line.c_str());
      };
    for (uint32_t i = 0; i < engine->enabledExtensionCount; ++i)
      if (!engine->enabledExtensions[i])
        throw std::invalid_argument("sixwayCreateEngineDevice: enabledExtensions[" + std::to_string(i) +
                                    "] is null");
    for (uint32_t i = 0; i < engine->enabledExtensionCount; ++i)
      e.enabledExtensions.emplace_back(engine->enabledExtensions[i]);
    if (engine->submitAndWait)
      e.submitAndWait = [submit = engine->submitAndWait,
                         user = engine->submitUser](const std::function<void(VkCommandBuffer)>& record) {
        Recording recording{&record, nullptr};
        submit(user, recordTrampoline, &recording);
        if (recording.failure) std::rethrow_exception(recording.failure);
      };
    *device = new SixwayDevice_T{sixway::Device(e)};
  });
}

SixwayResult sixwayDeviceHostWaits(SixwayDevice device, uint64_t* waits) {
  if (!device || !waits) return nullArgument("sixwayDeviceHostWaits", !device ? "device" : "waits");
  *waits = device->device.hostWaits();
  return SIXWAY_SUCCESS;
}

void sixwayDestroyDevice(SixwayDevice device) {
  delete device;
}

SixwayResult sixwayCreateSimulation(SixwayDevice device, const char* scenePath,
                                    SixwaySimulation* simulation) {
  if (!device || !scenePath || !simulation)
    return nullArgument("sixwayCreateSimulation", !device      ? "device"
                                                  : !scenePath ? "scenePath"
                                                               : "simulation");
  *simulation = nullptr;
  return guarded(
      [&] { *simulation = new SixwaySimulation_T{sixway::SmokeSimulation(device->device, scenePath)}; });
}

SixwayResult sixwayCreateSimulationFromText(SixwayDevice device, const char* json, size_t length,
                                            const char* directory, SixwaySimulation* simulation) {
  if (!device || !json || !simulation)
    return nullArgument("sixwayCreateSimulationFromText", !device ? "device" : !json ? "json" : "simulation");
  *simulation = nullptr;
  return guarded([&] {
    const sixway::SceneText text{.json = std::string_view(json, length),
                                 .directory = directory ? directory : "."};
    *simulation = new SixwaySimulation_T{sixway::SmokeSimulation(device->device, text)};
  });
}

void sixwaySmokeDomainDefaults(SixwaySmokeDomain* domain) {
  if (!domain) return;
  const sixway::SmokeDomain d;
  *domain = {{d.cells.x, d.cells.y, d.cells.z},
             d.cellSize,
             {d.origin.x, d.origin.y, d.origin.z},
             d.frameSeconds,
             d.viscosity,
             d.buoyancy,
             d.extinction,
             d.albedo,
             d.phaseG,
             d.dissipation,
             d.lightmapSize};
}

SixwayResult sixwayCreateSimulationFromDomain(SixwayDevice device, const SixwaySmokeDomain* domain,
                                              SixwaySimulation* simulation) {
  if (!device || !domain || !simulation)
    return nullArgument("sixwayCreateSimulationFromDomain", !device   ? "device"
                                                            : !domain ? "domain"
                                                                      : "simulation");
  *simulation = nullptr;
  return guarded([&] {
    const sixway::SmokeDomain d{glm::make_vec3(domain->cells),
                                domain->cellSize,
                                glm::make_vec3(domain->origin),
                                domain->frameSeconds,
                                domain->viscosity,
                                domain->buoyancy,
                                domain->extinction,
                                domain->albedo,
                                domain->phaseG,
                                domain->dissipation,
                                domain->lightmapSize};
    *simulation = new SixwaySimulation_T{sixway::SmokeSimulation(device->device, d)};
  });
}

SixwayResult sixwaySimulationAdvance(SixwaySimulation simulation) {
  if (!simulation) return nullArgument("sixwaySimulationAdvance", "simulation");
  return guarded([&] { simulation->simulation.advance(); });
}

SixwayResult sixwaySimulationRecord(SixwaySimulation simulation, VkCommandBuffer commands, uint64_t frame) {
  if (!simulation) return nullArgument("sixwaySimulationRecord", "simulation");
  return guarded([&] { simulation->simulation.record(commands, frame); });
}

SixwayResult sixwaySimulationRecordSeconds(SixwaySimulation simulation, VkCommandBuffer commands,
                                           uint64_t frame, double seconds, uint32_t* steps) {
  if (!simulation) return nullArgument("sixwaySimulationRecordSeconds", "simulation");
  return guarded([&] {
    const uint32_t recorded = simulation->simulation.record(commands, frame, seconds);
    if (steps) *steps = recorded;
  });
}

SixwayResult sixwaySimulationSetPlacement(SixwaySimulation simulation, const float worldFromScene[16]) {
  if (!simulation || !worldFromScene)
    return nullArgument("sixwaySimulationSetPlacement", !simulation ? "simulation" : "worldFromScene");
  return guarded([&] { simulation->simulation.setPlacement(glm::make_mat4(worldFromScene)); });
}

SixwayResult sixwaySimulationObstacleCount(SixwaySimulation simulation, uint32_t* count) {
  if (!simulation || !count)
    return nullArgument("sixwaySimulationObstacleCount", !simulation ? "simulation" : "count");
  *count = uint32_t(simulation->simulation.obstacleCount());
  return SIXWAY_SUCCESS;
}

SixwayResult sixwaySimulationObstaclePosition(SixwaySimulation simulation, uint32_t obstacle,
                                              float position[3]) {
  if (!simulation || !position)
    return nullArgument("sixwaySimulationObstaclePosition", !simulation ? "simulation" : "position");
  return guarded([&] {
    const glm::vec3 p = simulation->simulation.obstaclePosition(obstacle);
    std::copy(&p.x, &p.x + 3, position);
  });
}

SixwayResult sixwaySimulationSteerObstacle(SixwaySimulation simulation, uint32_t obstacle,
                                           const float target[3], double seconds) {
  if (!simulation || !target)
    return nullArgument("sixwaySimulationSteerObstacle", !simulation ? "simulation" : "target");
  return guarded([&] { simulation->simulation.steerObstacle(obstacle, glm::make_vec3(target), seconds); });
}

SixwayResult sixwaySimulationSetEmitters(SixwaySimulation simulation, const SixwayEmitter* emitters,
                                         uint32_t count) {
  if (!simulation || (count > 0 && !emitters))
    return nullArgument("sixwaySimulationSetEmitters", !simulation ? "simulation" : "emitters");
  return guarded([&] {
    std::vector<sixway::Emitter> list;
    for (uint32_t i = 0; i < count; ++i) {
      const SixwayEmitter& e = emitters[i];
      list.push_back({glm::make_vec3(e.position), e.radius, glm::make_vec3(e.velocity), e.densityRate,
                      e.temperatureRate, e.on != 0});
    }
    simulation->simulation.setEmitters(list);
  });
}

SixwayResult sixwaySimulationSetObstacles(SixwaySimulation simulation, const SixwayObstacle* obstacles,
                                          uint32_t count, double seconds) {
  if (!simulation || (count > 0 && !obstacles))
    return nullArgument("sixwaySimulationSetObstacles", !simulation ? "simulation" : "obstacles");
  return guarded([&] {
    std::vector<sixway::Obstacle> list;
    for (uint32_t i = 0; i < count; ++i) {
      const SixwayObstacle& o = obstacles[i];
      if (o.shape != SIXWAY_OBSTACLE_SPHERE && o.shape != SIXWAY_OBSTACLE_BOX &&
          o.shape != SIXWAY_OBSTACLE_CAPSULE && o.shape != SIXWAY_OBSTACLE_MESH)
        throw std::invalid_argument("sixwaySimulationSetObstacles: obstacle " + std::to_string(i) +
                                    " has no shape " + std::to_string(int(o.shape)));
      if (o.shape == SIXWAY_OBSTACLE_MESH &&
          ((o.vertexCount > 0 && !o.vertices) || (o.indexCount > 0 && !o.indices)))
        throw std::invalid_argument("sixwaySimulationSetObstacles: obstacle " + std::to_string(i) +
                                    ": vertices or indices are null");
      static_assert(sizeof(glm::vec3) == 3 * sizeof(float));  // the vertices viewed in place
      sixway::Obstacle obstacle{sixway::Obstacle::Shape(o.shape),
                                glm::make_vec3(o.position),
                                o.radius,
                                glm::make_vec3(o.size),
                                o.height,
                                glm::make_vec3(o.axis)};
      obstacle.shadows = o.shadows != 0;
      if (o.shape == SIXWAY_OBSTACLE_MESH) {
        obstacle.vertices = {reinterpret_cast<const glm::vec3*>(o.vertices), o.vertexCount};
        obstacle.indices = {o.indices, o.indexCount};
        const glm::mat3 rotation = glm::make_mat3(o.rotation);
        obstacle.rotation = rotation == glm::mat3(0.0f) ? glm::mat3(1.0f) : rotation;
        obstacle.scale = o.scale;
      }
      list.push_back(obstacle);
    }
    simulation->simulation.setObstacles(list, seconds);
  });
}

void sixwayDestroySimulation(SixwaySimulation simulation) {
  delete simulation;
}

SixwayResult sixwayCreateRenderer(SixwayDevice device, SixwaySimulation simulation, const char* weightsPath,
                                  const SixwayRenderTarget* target, SixwayRenderer* renderer) {
  if (!device || !simulation || !weightsPath || !renderer)
    return nullArgument("sixwayCreateRenderer", !device        ? "device"
                                                : !simulation  ? "simulation"
                                                : !weightsPath ? "weightsPath"
                                                               : "renderer");
  *renderer = nullptr;
  return guarded([&] {
    const sixway::RendererOptions options{.weights = weightsPath};
    if (!target) {
      *renderer =
          new SixwayRenderer_T{sixway::SmokeRenderer(device->device, simulation->simulation, options)};
      return;
    }
    const sixway::RenderTarget t{target->colorImage, target->colorView, target->colorFormat,
                                 target->depthImage, target->depthView, target->depthFormat,
                                 target->width,      target->height};
    *renderer =
        new SixwayRenderer_T{sixway::SmokeRenderer(device->device, simulation->simulation, options, t)};
  });
}

SixwayResult sixwayRendererSetViewProjection(SixwayRenderer renderer, const float view[16],
                                             const float projection[16]) {
  if (!renderer || !view || !projection)
    return nullArgument("sixwayRendererSetViewProjection", !renderer ? "renderer"
                                                           : !view   ? "view"
                                                                     : "projection");
  return guarded(
      [&] { renderer->renderer.setViewProjection(glm::make_mat4(view), glm::make_mat4(projection)); });
}

SixwayResult sixwayRendererSetLights(SixwayRenderer renderer, const SixwayLight* lights, uint32_t count) {
  if (!renderer || (count > 0 && !lights))
    return nullArgument("sixwayRendererSetLights", !renderer ? "renderer" : "lights");
  return guarded([&] {
    std::vector<sixway::Light> list;
    for (uint32_t i = 0; i < count; ++i) {
      const SixwayLight& l = lights[i];
      if (l.kind != 0 && l.kind != 1)
        throw std::invalid_argument("sixwayRendererSetLights: lights[" + std::to_string(i) + "].kind " +
                                    std::to_string(l.kind) + " is not 0 or 1");
      list.push_back({l.kind == 0 ? sixway::Light::Kind::Directional : sixway::Light::Kind::Point,
                      glm::make_vec3(l.direction), glm::make_vec3(l.position), glm::make_vec3(l.color),
                      l.intensity, l.shadows != 0});
    }
    renderer->renderer.setLights(list);
  });
}

SixwayResult sixwayRendererRecord(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame) {
  if (!renderer) return nullArgument("sixwayRendererRecord", "renderer");
  return guarded([&] { renderer->renderer.record(commands, frame); });
}

SixwayResult sixwayCreateRendererForFormat(SixwayDevice device, SixwaySimulation simulation,
                                           const char* weightsPath, VkFormat colorFormat,
                                           SixwayRenderer* renderer) {
  if (!device || !simulation || !weightsPath || !renderer)
    return nullArgument("sixwayCreateRendererForFormat", !device        ? "device"
                                                         : !simulation  ? "simulation"
                                                         : !weightsPath ? "weightsPath"
                                                                        : "renderer");
  *renderer = nullptr;
  return guarded([&] {
    *renderer = new SixwayRenderer_T{
        sixway::SmokeRenderer(device->device, simulation->simulation, {.weights = weightsPath}, colorFormat)};
  });
}

SixwayResult sixwayCreateRendererFromInfo(SixwayDevice device, SixwaySimulation simulation,
                                          const SixwayRendererInfo* info, SixwayRenderer* renderer) {
  if (!device || !simulation || !info || !renderer)
    return nullArgument("sixwayCreateRendererFromInfo", !device       ? "device"
                                                        : !simulation ? "simulation"
                                                        : !info       ? "info"
                                                                      : "renderer");
  *renderer = nullptr;
  if (!info->weightsPath && !info->weightsData && !info->shareNetwork)
    return fail(SIXWAY_ERROR_INVALID_ARGUMENT, "sixwayCreateRendererFromInfo", ": ",
                "info has no network (weightsPath, weightsData and shareNetwork are null)");
  if (info->renderingColorCount > 0 && !info->renderingColors)
    return nullArgument("sixwayCreateRendererFromInfo", "info->renderingColors");
  if (info->weightsData && info->weightsSize == 0)
    return fail(SIXWAY_ERROR_INVALID_ARGUMENT, "sixwayCreateRendererFromInfo", ": ",
                "info->weightsSize is 0");
  return guarded([&] {
    sixway::RendererOptions options;
    if (info->weightsPath) options.weights = info->weightsPath;
    if (info->weightsData)
      options.weightsData = std::span(static_cast<const std::byte*>(info->weightsData), info->weightsSize);
    if (info->shareNetwork) options.shareNetwork = &info->shareNetwork->renderer;
    if (info->lightmapPacking < 0 || info->lightmapPacking > 2)
      throw std::invalid_argument("sixwayCreateRendererFromInfo: lightmapPacking " +
                                  std::to_string(info->lightmapPacking) + " is not 0, 1 or 2");
    options.packing = sixway::LightmapPacking(info->lightmapPacking);
    if (info->renderingColorCount > 0) {
      const sixway::RenderingFormats formats{
          {info->renderingColors, info->renderingColors + info->renderingColorCount},
          info->renderingDepth,
          info->renderingStencil};
      *renderer = new SixwayRenderer_T{
          sixway::SmokeRenderer(device->device, simulation->simulation, options, formats)};
    } else {
      *renderer = new SixwayRenderer_T{
          sixway::SmokeRenderer(device->device, simulation->simulation, options, info->colorFormat)};
    }
  });
}

SixwayResult sixwayRendererRecordLightmaps(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame,
                                           const SixwayCompositeTargets* targets) {
  if (!renderer || !targets)
    return nullArgument("sixwayRendererRecordLightmaps", !renderer ? "renderer" : "targets");
  return guarded([&] {
    renderer->renderer.recordLightmaps(
        commands, frame,
        {targets->depth, targets->depthView, targets->depthFormat, targets->depthLayout, targets->width,
         targets->height, targets->viewport});
  });
}

SixwayResult sixwayRendererRecordComposite(SixwayRenderer renderer, VkCommandBuffer commands) {
  if (!renderer) return nullArgument("sixwayRendererRecordComposite", "renderer");
  return guarded([&] { renderer->renderer.recordComposite(commands); });
}

SixwayResult sixwayRendererRecordTargets(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame,
                                         const SixwayFrameTargets* targets) {
  if (!renderer || !targets)
    return nullArgument("sixwayRendererRecordTargets", !renderer ? "renderer" : "targets");
  auto image = [](const SixwayTargetImage& i) {
    return sixway::TargetImage{i.image, i.view, i.format, i.layout, i.finalLayout};
  };
  return guarded([&] {
    renderer->renderer.record(
        commands, frame,
        {image(targets->color), image(targets->depth), targets->width, targets->height, targets->viewport});
  });
}

SixwayResult sixwayRendererRender(SixwayRenderer renderer) {
  if (!renderer) return nullArgument("sixwayRendererRender", "renderer");
  return guarded([&] { renderer->renderer.render(); });
}

SixwayResult sixwayRendererSize(SixwayRenderer renderer, uint32_t* width, uint32_t* height) {
  if (!renderer || !width || !height)
    return nullArgument("sixwayRendererSize", !renderer ? "renderer" : !width ? "width" : "height");
  *width = renderer->renderer.width();
  *height = renderer->renderer.height();
  return SIXWAY_SUCCESS;
}

SixwayResult sixwayRendererImage(SixwayRenderer renderer, float* pixels, size_t count) {
  if (!renderer || !pixels) return nullArgument("sixwayRendererImage", !renderer ? "renderer" : "pixels");
  return guarded([&] {
    const size_t size = size_t(renderer->renderer.width()) * renderer->renderer.height() * 4;
    if (count != size)
      throw std::invalid_argument("sixwayRendererImage: " + std::to_string(count) +
                                  " floats given, the image has " + std::to_string(size));
    const std::vector<float> image = renderer->renderer.image();
    std::copy(image.begin(), image.end(), pixels);
  });
}

SixwayResult sixwayRendererLightmaps(SixwayRenderer renderer, SixwayLightmapTextures* lightmaps) {
  if (!renderer || !lightmaps)
    return nullArgument("sixwayRendererLightmaps", !renderer ? "renderer" : "lightmaps");
  return guarded([&] {
    const sixway::LightmapTextures t = renderer->renderer.lightmaps();
    *lightmaps = {t.a, t.b, t.viewA, t.viewB, t.format, t.width, t.height, {}};
    for (int c = 0; c < 4; ++c) std::copy(&t.corners[c].x, &t.corners[c].x + 3, lightmaps->corners[c]);
  });
}

SixwayResult sixwayRendererForgetTargets(SixwayRenderer renderer) {
  if (!renderer) return nullArgument("sixwayRendererForgetTargets", "renderer");
  renderer->renderer.forgetTargets();
  return SIXWAY_SUCCESS;
}

void sixwayDestroyRenderer(SixwayRenderer renderer) {
  delete renderer;
}

}  // extern "C"
