// The engine's host hooks on its device (EngineDevice): allocation callbacks that see every host allocation
// of sixway's Vulkan objects, each freed again; the engine's pipeline cache used instead of a cache file;
// notes to the engine's log instead of stderr; the engine's device-memory sub-allocator for every buffer and
// image, with the same image as sixway's own allocations and its exhaustion a LimitError.
#include <gtest/gtest.h>
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "gpu/check.h"
#include "gpu/device_features.h"
#include "gpu/pipeline.h"
#include "runtime/engine_harness.h"
#include "support/temp_dir.h"

namespace sixway::test {
namespace {

// An engine's host allocator: counts, and knows every live block's size for reallocation.
struct CountingAllocator {
  std::mutex mutex;
  std::map<void*, size_t> live;
  uint64_t allocations = 0;

  VkAllocationCallbacks callbacks() {
    VkAllocationCallbacks c{};
    c.pUserData = this;
    c.pfnAllocation = [](void* user, size_t size, size_t alignment, VkSystemAllocationScope) -> void* {
      return static_cast<CountingAllocator*>(user)->allocate(size, alignment);
    };
    c.pfnReallocation = [](void* user, void* old, size_t size, size_t alignment,
                           VkSystemAllocationScope) -> void* {
      auto* self = static_cast<CountingAllocator*>(user);
      if (!old) return self->allocate(size, alignment);
      if (size == 0) {
        self->release(old);
        return nullptr;
      }
      void* fresh = self->allocate(size, alignment);
      if (!fresh) return nullptr;
      std::memcpy(fresh, old, std::min(size, self->sizeOf(old)));
      self->release(old);
      return fresh;
    };
    c.pfnFree = [](void* user, void* memory) { static_cast<CountingAllocator*>(user)->release(memory); };
    return c;
  }
  void* allocate(size_t size, size_t alignment) {
    void* memory = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    std::lock_guard lock(mutex);
    if (memory) {
      live[memory] = size;
      ++allocations;
    }
    return memory;
  }
  size_t sizeOf(void* memory) {
    std::lock_guard lock(mutex);
    return live.at(memory);
  }
  void release(void* memory) {
    if (!memory) return;
    {
      std::lock_guard lock(mutex);
      live.erase(memory);
    }
    std::free(memory);
  }
};

// XDG_CACHE_HOME set for the test (sixway's cache file goes below it), the earlier values back after it.
// Mesa's shader cache stays where it was (MESA_SHADER_CACHE_DIR): compiling every shader afresh costs
// lavapipe most of a minute.
class CacheHome {
 public:
  explicit CacheHome(const std::filesystem::path& dir) {
    const char* home = std::getenv("HOME");
    old_ = value("XDG_CACHE_HOME");
    oldMesa_ = value("MESA_SHADER_CACHE_DIR");
    if (!oldMesa_ && (old_ || home))
      ::setenv("MESA_SHADER_CACHE_DIR",
               (old_ ? std::filesystem::path(*old_) : std::filesystem::path(home) / ".cache")
                   .append("mesa_shader_cache")
                   .c_str(),
               1);
    ::setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  }
  ~CacheHome() {
    restore("XDG_CACHE_HOME", old_);
    restore("MESA_SHADER_CACHE_DIR", oldMesa_);
  }

 private:
  static std::optional<std::string> value(const char* name) {
    const char* v = std::getenv(name);
    return v ? std::optional<std::string>(v) : std::nullopt;
  }
  static void restore(const char* name, const std::optional<std::string>& v) {
    if (v)
      ::setenv(name, v->c_str(), 1);
    else
      ::unsetenv(name);
  }
  std::optional<std::string> old_, oldMesa_;
};

// An engine's device-memory sub-allocator: chunks of 64 MiB per memory type (larger blocks get their own),
// handed out in aligned slices and never reused; host-visible chunks mapped whole.
struct ChunkAllocator {
  struct Chunk {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0, used = 0;
    void* mapped = nullptr;
  };
  VkDevice device;
  VkPhysicalDeviceMemoryProperties properties{};
  std::map<uint32_t, std::vector<Chunk>> chunks;
  uint64_t blocks = 0, freed = 0;
  bool exhausted = false;  // answer every request with no memory

  explicit ChunkAllocator(const gpu::Context& context) : device(context.device()) {
    vkGetPhysicalDeviceMemoryProperties(context.physicalDevice(), &properties);
  }
  ~ChunkAllocator() {
    for (auto& [type, list] : chunks)
      for (Chunk& c : list) vkFreeMemory(device, c.memory, nullptr);
  }
  DeviceMemoryAllocator hooks() {
    return {[this](const VkMemoryRequirements& r, uint32_t type, bool map) { return allocate(r, type, map); },
            [this](const MemoryBlock&) { ++freed; }};
  }
  static VkDeviceSize aligned(VkDeviceSize offset, VkDeviceSize alignment) {
    return (offset + alignment - 1) / alignment * alignment;
  }
  MemoryBlock allocate(const VkMemoryRequirements& r, uint32_t type, bool map) {
    if (exhausted) return {};
    std::vector<Chunk>& list = chunks[type];
    if (list.empty() || aligned(list.back().used, r.alignment) + r.size > list.back().size) {
      Chunk c;
      c.size = std::max<VkDeviceSize>(r.size, VkDeviceSize(64) << 20);
      VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, c.size, type};
      if (vkAllocateMemory(device, &info, nullptr, &c.memory) != VK_SUCCESS) return {};
      if (properties.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
        SIXWAY_VK(vkMapMemory(device, c.memory, 0, VK_WHOLE_SIZE, 0, &c.mapped));
      list.push_back(c);
    }
    Chunk& c = list.back();
    const VkDeviceSize offset = aligned(c.used, r.alignment);
    c.used = offset + r.size;
    ++blocks;
    return {c.memory, offset, map && c.mapped ? static_cast<std::byte*>(c.mapped) + offset : nullptr, blocks};
  }
};

// The engine's device as BorrowingEngine has it, with hooks.
Device hookedDevice(const gpu::Context& context, gpu::DeviceFeatures& features,
                    const VkAllocationCallbacks* allocator, VkPipelineCache cache,
                    std::function<void(const std::string&)> log, DeviceMemoryAllocator memory = {}) {
  const std::vector<const char*> extensions = gpu::requiredDeviceExtensions();
  EngineDevice engine{context.instance(),    context.physicalDevice(),
                      context.device(),      context.queue(),
                      context.queueFamily(), {extensions.begin(), extensions.end()},
                      features.chain(),      2};
  engine.allocator = allocator;
  engine.pipelineCache = cache;
  engine.log = std::move(log);
  engine.memory = std::move(memory);
  return Device(engine);
}

TEST(EngineHooks, AllocationsGoThroughTheEnginesCallbacksAndPipelinesThroughItsCache) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  const CacheHome cacheHome(dir.path() / "cache");
  Device own({.validate = true});
  BorrowingEngine engine(own);
  CountingAllocator allocator;
  const VkAllocationCallbacks callbacks = allocator.callbacks();
  VkPipelineCacheCreateInfo cacheInfo{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  VkPipelineCache cache = VK_NULL_HANDLE;
  SIXWAY_VK(vkCreatePipelineCache(engine.context.device(), &cacheInfo, nullptr, &cache));
  std::vector<std::string> lines;
  {
    Device device = hookedDevice(engine.context, engine.features, &callbacks, cache,
                                 [&](const std::string& line) { lines.push_back(line); });
    EngineTargets targets(engine.context, 64, 64);
    SmokeSimulation simulation(device, scene);
    SmokeRenderer renderer(device, simulation, {.weights = kWeights}, targets.target());
    renderer.setCamera(sceneCamera());
    const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    recordFrames(engine, targets, simulation, renderer, background);
    EXPECT_GT(allocator.allocations, 0u) << "no host allocation went through the engine's callbacks";
    // lavapipe keeps its compiled shaders in Mesa's own disk cache and writes nothing but the 32-byte
    // header into a VkPipelineCache, so the handle is what can be checked here.
    EXPECT_EQ(runtime::Access::pipelineCache(device).handle(), cache);
  }
  EXPECT_TRUE(allocator.live.empty()) << allocator.live.size() << " allocations left after destruction";
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "cache" / "sixway"))
      << "a pipeline cache file was written beside the engine's cache";
  EXPECT_TRUE(lines.empty());
  vkDestroyPipelineCache(engine.context.device(), cache, nullptr);
  EXPECT_EQ(own.validationMessages(), 0u);
}

// Without the engine's cache, sixway's own cache file; one that is a directory is a note, which goes to the
// engine's log and not to stderr.
TEST(EngineHooks, NotesGoToTheEnginesLog) {
  TempDir dir;
  const CacheHome cacheHome(dir.path() / "cache");
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const std::filesystem::path file = gpu::defaultPipelineCacheFile(engine.context);
  std::filesystem::create_directories(file);  // where the file belongs: a directory
  std::vector<std::string> lines;
  ::testing::internal::CaptureStderr();
  {
    Device device = hookedDevice(engine.context, engine.features, nullptr, VK_NULL_HANDLE,
                                 [&](const std::string& line) { lines.push_back(line); });
  }
  const std::string printed = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("is a directory"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find(file.string()), std::string::npos) << lines[0];
  EXPECT_EQ(printed, "");
  EXPECT_EQ(own.validationMessages(), 0u);
}

TEST(EngineHooks, BuffersAndImagesTakeTheirMemoryFromTheEnginesAllocator) {
  TempDir dir;
  const std::filesystem::path scene = sceneWithoutObstacles(dir.path());
  Device own({.validate = true});
  BorrowingEngine engine(own);
  const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  EngineTargets targets(engine.context, 64, 64);
  std::vector<float> expected;
  {
    SmokeSimulation simulation(engine.device, scene);
    SmokeRenderer renderer(engine.device, simulation, {.weights = kWeights}, targets.target());
    renderer.setCamera(sceneCamera());
    recordFrames(engine, targets, simulation, renderer, background);
    expected = targets.colorPixels();
  }
  ChunkAllocator chunks(engine.context);
  {
    Device device =
        hookedDevice(engine.context, engine.features, nullptr, VK_NULL_HANDLE, {}, chunks.hooks());
    SmokeSimulation simulation(device, scene);
    SmokeRenderer renderer(device, simulation, {.weights = kWeights}, targets.target());
    renderer.setCamera(sceneCamera());
    recordFrames(engine, targets, simulation, renderer, background);
    EXPECT_EQ(maxDifference(targets.colorPixels(), expected), 0.0);
    EXPECT_GT(chunks.blocks, 0u);
    EXPECT_EQ(chunks.blocks - chunks.freed, device.memoryUse().allocations)
        << "a buffer or image did not take its memory from the engine";
    chunks.exhausted = true;
    EXPECT_THROW(SmokeSimulation another(device, scene), Error) << "an exhausted allocator is a LimitError";
  }
  EXPECT_EQ(chunks.freed, chunks.blocks) << "blocks not given back";
  EXPECT_EQ(own.validationMessages(), 0u);
}

}  // namespace
}  // namespace sixway::test
