#pragma once
// A gpu::Sequence recorded once and replayed while the things it was recorded with (buffers, dispatch
// shapes) stay the same; per-frame values travel in uniform buffers, so most frames record nothing.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "gpu/sequence.h"

namespace sixway::render {

class RecordedSequence {
 public:
  explicit RecordedSequence(const gpu::Context& context) : context_(&context) {}

  // The sequence recorded for `key`; `record` fills a fresh one when the key differs from the last one.
  gpu::Sequence& get(const std::vector<uint64_t>& key, const std::function<void(gpu::Sequence&)>& record) {
    if (!sequence_ || key != key_) {
      sequence_.reset();
      auto fresh = std::make_unique<gpu::Sequence>(*context_);
      record(*fresh);
      fresh->finish();
      sequence_ = std::move(fresh);
      key_ = key;
      ++recordings_;
    }
    return *sequence_;
  }
  // The sequence recorded last, handed over (to keep while frames in flight run it); the next get() records
  // a fresh one.
  std::unique_ptr<gpu::Sequence> release() {
    key_.clear();
    return std::move(sequence_);
  }
  // How many times a sequence was recorded: what was recorded with an earlier one may be gone.
  uint64_t recordings() const { return recordings_; }

 private:
  const gpu::Context* context_;
  std::vector<uint64_t> key_;
  std::unique_ptr<gpu::Sequence> sequence_;
  uint64_t recordings_ = 0;
};

// The handle of a Vulkan object as a key element.
template <typename Handle>
uint64_t handleKey(Handle handle) {
  return reinterpret_cast<uint64_t>(handle);
}

}  // namespace sixway::render
