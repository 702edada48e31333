#include <sixway/device.h>

#include "gpu/device_features.h"
#include "runtime/device_impl.h"

namespace sixway {
namespace {

std::unique_ptr<Device::Impl> withCache(std::unique_ptr<gpu::Context> context) {
  auto impl = std::make_unique<Device::Impl>();
  impl->context = std::move(context);
  impl->cache =
      std::make_unique<gpu::PipelineCache>(*impl->context, gpu::defaultPipelineCacheFile(*impl->context));
  return impl;
}

}  // namespace

struct DeviceRequirements::Impl {
  std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
  gpu::DeviceFeatures features;
};

DeviceRequirements::DeviceRequirements(VkPhysicalDevice physicalDevice) : impl_(std::make_unique<Impl>()) {
  impl_->features = gpu::DeviceFeatures::toEnable(gpu::DeviceFeatures::supportedBy(physicalDevice));
}

DeviceRequirements::~DeviceRequirements() = default;

const std::vector<const char*>& DeviceRequirements::extensions() const {
  return impl_->extensions;
}

VkPhysicalDeviceFeatures2* DeviceRequirements::features() {
  return impl_->features.chain();
}

Device::Device(const DeviceOptions& options) {
  gpu::ContextOptions contextOptions;
  contextOptions.validate = options.validate;
  contextOptions.deviceIndex = options.index;
  impl_ = withCache(std::make_unique<gpu::Context>(contextOptions));
}

Device::Device(const EngineDevice& engine) {
  gpu::ExternalDevice external{engine.instance,        engine.physicalDevice, engine.device,
                               engine.queue,           engine.queueFamily,    engine.enabledExtensions,
                               engine.enabledFeatures, engine.framesInFlight};
  impl_ = withCache(std::make_unique<gpu::Context>(external));
}

Device::~Device() = default;

std::string Device::name() const {
  return impl_->context->properties().deviceName;
}

uint64_t Device::hostWaits() const {
  return impl_->context->hostWaits();
}

uint32_t Device::validationMessages() const {
  return impl_->context->validationMessageCount();
}

}  // namespace sixway
