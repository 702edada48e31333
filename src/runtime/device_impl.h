#pragma once
// What a sixway::Device holds: the gpu::Context (own or borrowed) and the pipeline cache every stage on it
// shares.
#include <sixway/device.h>

#include <memory>

#include "gpu/context.h"
#include "gpu/pipeline.h"

namespace sixway {

struct Device::Impl {
  // A device of its own: the context, and the pipeline cache in $XDG_CACHE_HOME/sixway (lavapipe compiles
  // once per machine).
  explicit Impl(std::unique_ptr<gpu::Context> own);
  // Around a context and cache that outlive the Device (the demo's window device).
  Impl(gpu::Context& context, gpu::PipelineCache& cache) : context(&context), cache(&cache) {}

  gpu::Context* context;
  gpu::PipelineCache* cache;

 private:
  std::unique_ptr<gpu::Context> ownContext_;
  std::unique_ptr<gpu::PipelineCache> ownCache_;
};

}  // namespace sixway
