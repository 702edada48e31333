#pragma once
// sixway's own tools' way behind the public API (include/sixway/): the Vulkan context and pipeline cache of a
// Device, the scene and volumes of a SmokeSimulation, the frame of a SmokeRenderer. Not installed: an engine
// sees include/sixway/ alone.
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <cstdint>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "runtime/realtime_frame.h"
#include "runtime/scene_volumes.h"
#include "scene/scene.h"

namespace sixway::runtime {

// What sixway's own device asks of the Vulkan host.
gpu::ContextOptions contextOptions(const DeviceOptions& options);

struct Access {
  // A Device around a context and cache that outlive it (the demo's window device).
  static Device borrowDevice(gpu::Context& context, gpu::PipelineCache& cache);
  static const gpu::Context& context(const Device& device);
  static const gpu::PipelineCache& pipelineCache(const Device& device);

  static const scene::Scene& scene(const SmokeSimulation& simulation);
  static const SimulatedVolumes& volumes(const SmokeSimulation& simulation);
  // How often the simulation was started: a restarted one's volume may reuse a buffer handle.
  static uint64_t starts(const SmokeSimulation& simulation);

  // The passes and images of the renderer's last frame.
  static const RealtimeFrame& frame(const SmokeRenderer& renderer);
};

}  // namespace sixway::runtime
