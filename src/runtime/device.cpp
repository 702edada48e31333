#include <sixway/device.h>

#include <stdexcept>

#include "gpu/cooperative_matrix.h"
#include "gpu/device_features.h"
#include "gpu/feature_merge.h"
#include "runtime/device_impl.h"
#include "runtime/internal.h"

namespace sixway {

Device::Impl::Impl(std::unique_ptr<gpu::Context> own)
    : context(own.get()),
      ownContext_(std::move(own)),
      ownCache_(std::make_unique<gpu::PipelineCache>(
          *context, context->externalPipelineCache() ? std::filesystem::path()
                                                     : gpu::defaultPipelineCacheFile(*context))) {
  cache = ownCache_.get();
}

struct DeviceRequirements::Impl {
  std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
  gpu::DeviceFeatures features;
  VkPhysicalDeviceCooperativeMatrixFeaturesNV matrix{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COOPERATIVE_MATRIX_FEATURES_NV};
  std::unique_ptr<gpu::FeatureMerge> merge;
};

DeviceRequirements::DeviceRequirements(VkPhysicalDevice physicalDevice) : impl_(std::make_unique<Impl>()) {
  impl_->features = gpu::DeviceFeatures::toEnable(gpu::DeviceFeatures::supportedBy(physicalDevice));
  // Optional: the network's conv2d on cooperative matrices (tensor cores) where the device has them.
  if (gpu::hasCooperativeMatrix(physicalDevice) && impl_->features.vulkan12().vulkanMemoryModel) {
    impl_->extensions.push_back(VK_NV_COOPERATIVE_MATRIX_EXTENSION_NAME);
    impl_->matrix.cooperativeMatrix = VK_TRUE;
    impl_->matrix.pNext = impl_->features.chain()->pNext;
    impl_->features.chain()->pNext = &impl_->matrix;
  }
}

DeviceRequirements::~DeviceRequirements() = default;

const std::vector<const char*>& DeviceRequirements::extensions() const {
  return impl_->extensions;
}

VkPhysicalDeviceFeatures2* DeviceRequirements::features() {
  return impl_->features.chain();
}

void DeviceRequirements::mergeInto(VkDeviceCreateInfo& info, std::vector<const char*>& extensions) {
  if (impl_->merge) throw std::invalid_argument("DeviceRequirements::mergeInto: one merge per object");
  impl_->merge = std::make_unique<gpu::FeatureMerge>(impl_->features, bool(impl_->matrix.cooperativeMatrix),
                                                     impl_->extensions, info, extensions);
}

Device::Device(const DeviceOptions& options)
    : impl_(std::make_unique<Impl>(std::make_unique<gpu::Context>(runtime::contextOptions(options)))) {}

Device::Device(const EngineDevice& engine) {
  gpu::ExternalDevice external{engine.instance,        engine.physicalDevice, engine.device,
                               engine.queue,           engine.queueFamily,    engine.enabledExtensions,
                               engine.enabledFeatures, engine.framesInFlight, engine.submitAndWait,
                               engine.allocator,       engine.pipelineCache,  engine.log};
  external.getInstanceProcAddr = engine.getInstanceProcAddr;
  if (engine.memory.allocate && engine.memory.free) {
    external.memory.allocate = [allocate = engine.memory.allocate](const VkMemoryRequirements& requirements,
                                                                   uint32_t type, bool map) {
      const MemoryBlock b = allocate(requirements, type, map);
      return gpu::MemoryBlock{b.memory, b.offset, b.mapped, b.token};
    };
    external.memory.free = [free = engine.memory.free](const gpu::MemoryBlock& b) {
      free(MemoryBlock{b.memory, b.offset, b.mapped, b.token});
    };
  } else if (engine.memory.allocate || engine.memory.free) {
    throw std::invalid_argument("EngineDevice::memory: needs both allocate and free");
  }
  impl_ = std::make_unique<Impl>(std::make_unique<gpu::Context>(external));
}

Device::Device(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

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

Device::MemoryUse Device::memoryUse() const {
  const gpu::MemoryUse use = impl_->context->memoryUse();
  return {use.allocations, use.bytes};
}

}  // namespace sixway
