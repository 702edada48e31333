#pragma once
// A recorded sequence of GPU work: dispatches, draws and copies in one (secondary) command buffer, recorded
// once and replayed as often as needed (once per frame): submitted on its own with submit(), which waits,
// or recorded into a caller's command buffer with record(), which does not (docs/embedding.md). Barriers are
// inserted where a command reads or writes what an earlier one wrote (or writes what an earlier one read),
// from the access each binding declares. Named stages are bracketed by GPU timestamps.
#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace sixway::gpu {

class Buffer;
class BufferView;
class Context;
class Image;
class Pipeline;
class Sampler;

enum class Access { Read, Write, ReadWrite };

struct BufferBinding {
  const Buffer* buffer;
  Access access;
};
struct ImageBinding {
  const Image* image;
  Access access;
  const Sampler* sampler = nullptr;  // set for BindingType::SampledImage
  // The layout the image is in where it is bound: sixway's images stay in GENERAL; an engine's depth buffer
  // read inside its own rendering is in a read-only depth layout.
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};
// A buffer read or written as texels (BindingType::StorageTexelBuffer); barriers follow the underlying
// buffer.
struct TexelBufferBinding {
  const BufferView* view;
  Access access;
};
using Binding = std::variant<BufferBinding, ImageBinding, TexelBufferBinding>;

inline Binding reads(const Buffer& b) {
  return BufferBinding{&b, Access::Read};
}
inline Binding writes(const Buffer& b) {
  return BufferBinding{&b, Access::Write};
}
inline Binding readsWrites(const Buffer& b) {
  return BufferBinding{&b, Access::ReadWrite};
}
inline Binding reads(const Image& i) {
  return ImageBinding{&i, Access::Read};
}
inline Binding writes(const Image& i) {
  return ImageBinding{&i, Access::Write};
}
inline Binding readsWrites(const Image& i) {
  return ImageBinding{&i, Access::ReadWrite};
}
inline Binding reads(const BufferView& v) {
  return TexelBufferBinding{&v, Access::Read};
}
inline Binding samples(const Image& i, const Sampler& s, VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL) {
  return ImageBinding{&i, Access::Read, &s, layout};
}

struct Draw {
  const Pipeline* pipeline;
  std::vector<Binding> bindings;
  std::vector<std::byte> pushConstants;
  const Buffer* vertices = nullptr;  // bound at binding 0, or none
  const Buffer* indices = nullptr;   // uint32 indices, or none
  uint32_t count = 0;                // vertices, or indices when there is an index buffer
  uint32_t instances = 1;
  // The viewport and scissor of this draw in pixels of the targets (row 0 at the top), e.g. one tile of an
  // atlas: clip space [-1, 1]² maps onto it, +y up. Unset: the whole targets.
  std::optional<VkRect2D> area;
};

struct RenderTargets {
  std::vector<const Image*> colors;
  const Image* depth = nullptr;
  std::optional<std::array<float, 4>> clearColor;  // otherwise the colour images are loaded
  std::optional<float> clearDepth;
};

struct StageTime {
  std::string name;
  double milliseconds;
};

template <typename T>
std::vector<std::byte> pushBytes(const T& value) {
  auto bytes = std::as_bytes(std::span(&value, 1));
  return {bytes.begin(), bytes.end()};
}

class Sequence {
 public:
  explicit Sequence(const Context& context, uint32_t maxStages = 64);
  ~Sequence();
  Sequence(const Sequence&) = delete;
  Sequence& operator=(const Sequence&) = delete;

  // Everything recorded between these two is timed as one stage (stages do not nest).
  void beginStage(std::string name);
  void endStage();

  void dispatch(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                std::span<const std::byte> pushConstants, uint32_t groupsX, uint32_t groupsY = 1,
                uint32_t groupsZ = 1);
  template <typename Push>
  void dispatch(const Pipeline& pipeline, const std::vector<Binding>& bindings, const Push& push,
                uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) {
    dispatch(pipeline, bindings, std::as_bytes(std::span(&push, 1)), groupsX, groupsY, groupsZ);
  }
  // A 1D kernel of `invocations` invocations, `groupSize` per workgroup: the workgroups go along x up to the
  // device's limit and wrap into y beyond it (Vulkan guarantees only 65535 along x: a 128×256×128 lattice at
  // 64 per group needs 65536). The shader indexes with linearInvocationIndex()
  // (shaders/common/linear_index.glsl) and skips indices ≥ invocations.
  void dispatchLinear(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                      std::span<const std::byte> pushConstants, uint64_t invocations, uint32_t groupSize);
  template <typename Push>
  void dispatchLinear(const Pipeline& pipeline, const std::vector<Binding>& bindings, const Push& push,
                      uint64_t invocations, uint32_t groupSize) {
    dispatchLinear(pipeline, bindings, std::as_bytes(std::span(&push, 1)), invocations, groupSize);
  }
  // A dispatch whose group counts the GPU reads from `args` at `offset` (VkDispatchIndirectCommand) when it
  // runs; zero groups dispatch nothing. `args` is written by the host between executions (a FrameParameters
  // buffer with VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT), so no barrier orders it against the recorded work.
  void dispatchIndirect(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                        std::span<const std::byte> pushConstants, const Buffer& args, uint64_t offset);
  template <typename Push>
  void dispatchIndirect(const Pipeline& pipeline, const std::vector<Binding>& bindings, const Push& push,
                        const Buffer& args, uint64_t offset) {
    dispatchIndirect(pipeline, bindings, std::as_bytes(std::span(&push, 1)), args, offset);
  }
  // One dynamic-rendering pass: the barriers for all draws are placed before it begins.
  void render(const RenderTargets& targets, std::span<const Draw> draws);
  void fill(const Buffer& buffer, uint32_t word);
  void copy(const Buffer& source, const Buffer& destination);

  // Ends recording; the sequence can then be submitted any number of times.
  void finish();
  // Submits, waits for completion and collects the stage times (through ExternalDevice::submitAndWait where
  // the device has one).
  void submit();
  // Records the sequence into `commands`, a primary command buffer being recorded outside a render pass, as
  // frame number `frame` (any increasing count): the frame-parameter buffers it binds are written into the
  // command buffer from their host copies (MemoryKind::FrameParameters), the work runs, and each readback
  // source is copied into the host slot of `frame`. Full barriers open and close it. Nothing waits: the
  // work is recorded once per frame in flight, and frame n runs the copy that frame n − framesInFlight ran,
  // whose stage times are collected now.
  void record(VkCommandBuffer commands, uint64_t frame);
  // Copies `source` (a device buffer) to the host after every execution recorded by record(), for readback().
  void addReadback(const Buffer& source);
  // The host copy of `source` made by the execution recorded as `frame`: valid once that execution has
  // completed. The slots are reused after Context::framesInFlight() further frames.
  std::span<const std::byte> readback(const Buffer& source, uint64_t frame) const;
  const std::vector<StageTime>& stageTimes() const { return times_; }
  // The stage times of the execution recorded as `frame`, which must have completed, read now (record()
  // reads a frame's times only when its copy of the work is recorded again, which a sequence that is not
  // recorded every frame may never be); stageTimes() then holds them, or still the last times read if the
  // GPU wrote none there.
  const std::vector<StageTime>& timesOfFrame(uint64_t frame);
  uint32_t barrierCount() const { return barriers_; }

 private:
  // The resources touched by a command, for barrier placement.
  struct Touch {
    std::vector<uint64_t> reads, writes;
  };
  void addTouch(Touch& touch, const Binding& binding) const;
  void barrierIfHazard(const Touch& touch);
  void requireRecording(const char* what) const;
  void writeTimestamp(uint32_t query);
  struct Slot {
    VkCommandBuffer commands = VK_NULL_HANDLE;  // secondary: the recorded work
    VkQueryPool queries = VK_NULL_HANDLE;
    mutable uint64_t executions = 0;
  };
  void collectTimes(const Slot& slot, bool wait);
  void recordInto(VkCommandBuffer commands, uint64_t frame, bool withReadbacks);
  void noteFrameParameters(const Binding& binding);
  void beginDispatch(const Pipeline& pipeline, const std::vector<Binding>& bindings,
                     std::span<const std::byte> pushConstants);

  const Context* context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::vector<Slot> slots_;                   // Context::framesInFlight() copies of the work
  VkCommandBuffer primary_ = VK_NULL_HANDLE;  // submit()'s command buffer around it
  VkFence fence_ = VK_NULL_HANDLE;
  uint64_t submissions_ = 0;
  // Frame-parameter buffers bound by the work: handle, host copy, bytes (a Buffer may move; these do not).
  struct FrameParameters {
    VkBuffer buffer;
    const std::byte* values;
    uint64_t bytes;
  };
  std::vector<FrameParameters> frameParameters_;
  struct Readback {
    VkBuffer source;
    uint64_t bytes;
    std::string name;
    std::vector<Buffer> slots;  // host memory, one per frame in flight + 1
  };
  std::vector<Readback> readbacks_;
  uint32_t maxStages_;
  std::vector<std::string> stageNames_;
  bool stageOpen_ = false;
  bool finished_ = false;
  bool resolveEachTimestamp_ = false;  // lavapipe: see writeTimestamp()
  std::set<uint64_t> writtenSinceBarrier_, readSinceBarrier_;
  std::vector<StageTime> times_;
  uint32_t barriers_ = 0;
};

// The workgroups of dispatchLinear(): x up to the device's limit, wrapping into y; throws GpuError naming
// `what` beyond the y limit.
VkDispatchIndirectCommand linearGroups(const Context& context, uint64_t invocations, uint32_t groupSize,
                                       const std::string& what);

}  // namespace sixway::gpu
