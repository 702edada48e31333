#include <sixway/smoke_simulation.h>

#include <limits>

#include "runtime/smoke_simulation_impl.h"

namespace sixway {

SmokeSimulation::Impl::Impl(Device::Impl& device, io::Scene scene)
    : device(device),
      scene(std::move(scene)),
      volumes(*device.context, *device.cache, this->scene, std::numeric_limits<int>::max()) {}

SmokeSimulation::SmokeSimulation(Device& device, const std::filesystem::path& scene)
    : impl_(std::make_unique<Impl>(device.impl(), io::loadScene(scene))) {}

SmokeSimulation::~SmokeSimulation() = default;

void SmokeSimulation::advance() {
  impl_->volumes.volume(impl_->frames);
  ++impl_->frames;
}

void SmokeSimulation::record(VkCommandBuffer commands, uint64_t frame) {
  impl_->volumes.recordFrame(commands, frame);
  ++impl_->frames;
}

SmokeVolume SmokeSimulation::volume() const {
  const render::Volume v = impl_->volumes.currentVolume();
  return {v.density->handle(), v.temperature ? v.temperature->handle() : VK_NULL_HANDLE, v.grid.size,
          v.grid.origin, v.grid.cellSize};
}

int SmokeSimulation::framesSimulated() const {
  return impl_->frames;
}

double SmokeSimulation::seconds() const {
  return impl_->volumes.simulation().seconds();
}

size_t SmokeSimulation::obstacleCount() const {
  return impl_->scene.obstacles.size();
}

void SmokeSimulation::steerObstacle(size_t obstacle, glm::vec3 target) {
  impl_->volumes.simulation().steerObstacle(obstacle, target);
}

void SmokeSimulation::setInletStrength(float strength) {
  impl_->volumes.simulation().setInletStrength(strength);
}

float SmokeSimulation::inletStrength() const {
  return impl_->volumes.simulation().inletStrength();
}

float SmokeSimulation::maxInletStrength() const {
  return impl_->volumes.simulation().maxInletStrength();
}

}  // namespace sixway
