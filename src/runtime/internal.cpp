#include "runtime/internal.h"

#include "runtime/device_impl.h"
#include "runtime/smoke_renderer_impl.h"
#include "runtime/smoke_simulation_impl.h"

namespace sixway::runtime {

gpu::ContextOptions contextOptions(const DeviceOptions& options) {
  gpu::ContextOptions context;
  context.validate = options.validate;
  context.deviceIndex = options.index;
  return context;
}

Device Access::borrowDevice(gpu::Context& context, gpu::PipelineCache& cache) {
  return Device(std::make_unique<Device::Impl>(context, cache));
}

const gpu::Context& Access::context(const Device& device) {
  return *device.impl_->context;
}

const gpu::PipelineCache& Access::pipelineCache(const Device& device) {
  return *device.impl_->cache;
}

const scene::Scene& Access::scene(const SmokeSimulation& simulation) {
  return simulation.impl_->scene;
}

const SimulatedVolumes& Access::volumes(const SmokeSimulation& simulation) {
  return *simulation.impl_->volumes;
}

uint64_t Access::starts(const SmokeSimulation& simulation) {
  return simulation.impl_->starts;
}

const RealtimeFrame& Access::frame(const SmokeRenderer& renderer) {
  return renderer.impl_->renderer.frame();
}

}  // namespace sixway::runtime
