#include "app/render_frame_source.h"

#include <cstdio>
#include <string>
#include <vector>

#include "app/device_limits.h"
#include "app/stop_on_signal.h"
#include "modes/scene_source.h"
#include "runtime/internal.h"
#include "runtime/scene_volumes.h"

namespace sixway::app {

RenderFrameSource::RenderFrameSource(sixway::Device& device, scene::Scene& scene,
                                     const std::filesystem::path& scenePath, int frames,
                                     const modes::ModeOptions& options)
    : device_(device), scene_(scene) {
  openSmoke(scenePath, frames);
  makeRenderer(scenePath, options);
}

RenderFrameSource::~RenderFrameSource() = default;

void RenderFrameSource::openSmoke(const std::filesystem::path& scenePath, int frames) {
  if (scene_.vdb) {
    playback_ = withinDeviceLimits(scenePath.string(), "vdb.voxels", [&] {
      return modes::openSceneVolumes(runtime::Access::context(device_),
                                     runtime::Access::pipelineCache(device_), scene_, frames,
                                     scenePath.string());
    });
  } else {
    withinDeviceLimits(scenePath.string(), gridSetting(scene_.grid), [&] {
      simulation_.emplace(device_, scenePath);
      return true;
    });
  }
}

void RenderFrameSource::makeRenderer(const std::filesystem::path& scenePath,
                                     const modes::ModeOptions& options) {
  const std::string settings = "render.lightmap_size, render.width or render.height";
  if (options.mode == modes::RenderMode::Neural && simulation_) {
    sixway::RendererOptions rendererOptions;
    rendererOptions.weights = options.weights;
    rendererOptions.fp16 = options.fp16;
    rendererOptions.shadows = options.shadows;
    renderer_ = withinDeviceLimits(scenePath.string(), settings, [&] {
      return std::make_unique<sixway::SmokeRenderer>(device_, *simulation_, rendererOptions);
    });
  } else {
    modeRenderer_ = withinDeviceLimits(scenePath.string(), settings, [&] {
      return std::make_unique<modes::ModeRenderer>(runtime::Access::context(device_),
                                                   runtime::Access::pipelineCache(device_), scene_, options);
    });
  }
}

void RenderFrameSource::warmUp(int frames) {
  if (!simulation_) return;
  for (int w = 0; w < frames; ++w) {
    throwIfStopped();
    simulation_->advance();
    std::printf("  warm-up %d/%d\n", w + 1, frames);
    std::fflush(stdout);
  }
}

modes::RenderedFrame RenderFrameSource::render(int index) {
  if (simulation_) simulation_->advance();
  modes::RenderedFrame frame =
      modeRenderer_
          ? modeRenderer_->render(
                index, runtime::SimulatedVolumes::frameSeconds(scene_, index),
                playback_ ? playback_->volume(index) : runtime::Access::volumes(*simulation_).currentVolume())
          : renderNeural();
  if (simulation_) {
    std::vector<gpu::StageTime> stages;
    for (const sixway::StageTime& t : simulation_->stageTimes()) stages.push_back({t.name, t.milliseconds});
    frame.stages.insert(frame.stages.begin(), stages.begin(), stages.end());
  }
  return frame;
}

modes::RenderedFrame RenderFrameSource::renderNeural() {
  renderer_->render();
  modes::RenderedFrame frame;
  frame.image = io::Image(int(renderer_->width()), int(renderer_->height()), {"R", "G", "B", "A"});
  frame.image.pixels = renderer_->image();
  for (const sixway::StageTime& t : renderer_->stageTimes()) frame.stages.push_back({t.name, t.milliseconds});
  frame.notes = renderer_->notes();
  return frame;
}

}  // namespace sixway::app
