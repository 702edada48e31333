#pragma once
// What a sixway::Device holds: the gpu::Context (own or borrowed) and the pipeline cache every stage on it
// shares.
#include <sixway/device.h>

#include <memory>

#include "gpu/context.h"
#include "gpu/pipeline.h"

namespace sixway {

struct Device::Impl {
  std::unique_ptr<gpu::Context> context;
  std::unique_ptr<gpu::PipelineCache> cache;  // $XDG_CACHE_HOME/sixway: lavapipe compiles once per machine
};

}  // namespace sixway
