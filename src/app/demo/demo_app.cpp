#include "app/demo/demo_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "app/demo/display_pass.h"
#include "app/demo/imgui_layer.h"
#include "app/demo/live_scene.h"
#include "app/demo/presenter.h"
#include "app/demo/window.h"
#include "gpu/pipeline.h"
#include "io/error.h"
#include "io/png.h"
#include "metrics/image_metrics.h"
#include "render/sixway.h"
#include "runtime/internal.h"
#include "sim/watchdog.h"

namespace sixway::app::demo {
namespace {

namespace fs = std::filesystem;

// Where the lightmap channel `channel` (sixWayChannelNames() order) lies in Unity's packing:
// A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive).
std::pair<bool, int> packedChannel(int channel) {
  static const std::array<std::pair<bool, int>, 8> where = {
      {{false, 0}, {true, 0}, {false, 1}, {true, 1}, {false, 2}, {true, 2}, {false, 3}, {true, 3}}};
  return where.at(size_t(channel));
}

io::Image downloadFrame(const gpu::Image& image) {
  io::Image out(int(image.desc().width), int(image.desc().height), {"R", "G", "B", "A"});
  const std::vector<uint16_t> half = image.download<uint16_t>();
  for (size_t i = 0; i < half.size(); ++i) out.pixels[i] = glm::unpackHalf1x16(half[i]);
  return out;
}

}  // namespace

Demo::Demo(const DemoOptions& options) : options_(options), vsync_(options.vsync) {
  if (options.script) script_.emplace(loadScript(*options.script));
  const scene::Scene scene = scene::loadScene(options.scene);  // bad input fails before a window opens
  gpu::ContextOptions contextOptions = runtime::contextOptions(options.device);
  gpu::checkRequestedDevice(contextOptions);
  window_ = std::make_unique<Window>(options.width, options.height, "sixway-demo");
  contextOptions.instanceExtensions = Window::requiredInstanceExtensions();
  contextOptions.presentation = true;
  context_ = std::make_unique<gpu::Context>(contextOptions);
  cache_ = std::make_unique<gpu::PipelineCache>(*context_, gpu::defaultPipelineCacheFile(*context_));
  presenter_ = std::make_unique<Presenter>(*context_, window_->handle(), vsync_);
  installInput();  // before ImGui, which chains to these callbacks
  imgui_ = std::make_unique<ImGuiLayer>(*context_, window_->handle(), *presenter_);
  display_ = std::make_unique<DisplayPass>(*context_, *cache_, presenter_->extent().width,
                                           presenter_->extent().height, presenter_->format());
  scenePath_ = options.scene;
  live_ = std::make_unique<LiveScene>(*context_, *cache_, options.scene,
                                      LiveSceneOptions{options.weights, options.fp16});
  camera_ = OrbitCamera::fromScene(scene.camera);
  lights_ = startingLights(scene);
  if (!fs::exists(options.weights)) {
    mode_ = modes::RenderMode::Reference;
    say("no network at " + options.weights.string() + ": neural mode is off (train one, or pass --weights)",
        true);
  }
  lastFrame_ = std::chrono::steady_clock::now();
}

Demo::~Demo() {
  if (context_) vkDeviceWaitIdle(context_->device());
}

int Demo::run() {
  while (!quit_ && !window_->shouldClose()) frame();
  if (!history_.empty()) {  // what the panel's graph showed, for the terminal and docs/demo.md
    const FrameStages mean = history_.mean();
    std::printf("sixway-demo: last %d frames: %.2f frames/s; mean GPU ms per frame:", history_.size(),
                history_.framesPerSecond());
    for (int s = 0; s < int(Stage::Count); ++s)
      std::printf(" %s %.2f,", stageName(Stage(s)), mean.milliseconds[s]);
    std::printf(" total %.2f\n", mean.total());
  }
  if (context_->validationMessageCount() > 0) {
    std::fprintf(stderr, "sixway-demo: error: %u validation messages\n", context_->validationMessageCount());
    return 1;
  }
  return failures_ > 0 ? 1 : 0;
}

void Demo::say(std::string message, bool error) {
  status_ = std::move(message);
  statusIsError_ = error;
  std::fprintf(error ? stderr : stdout, "sixway-demo: %s%s\n", error ? "error: " : "", status_.c_str());
}

void Demo::frame() {
  glfwPollEvents();
  if (script_) {
    for (const ScriptCommand& c : script_->beforeFrame()) {
      try {
        runScriptCommand(c);
      } catch (const std::exception& e) {
        ++failures_;
        say(options_.script->string() + ": line " + std::to_string(c.line) + ": " + e.what(), true);
        quit_ = true;
      }
      if (quit_) break;  // this frame still renders: a screenshot of the window may wait for it
    }
    if (script_->finished()) quit_ = true;
  }
  if (presenter_->update(vsync_)) {
    imgui_->swapchainChanged(*presenter_);
    display_ = std::make_unique<DisplayPass>(*context_, *cache_, presenter_->extent().width,
                                             presenter_->extent().height, presenter_->format());
  }
  std::vector<gpu::StageTime> stages;  // no simulation's while paused
  if (!paused_ || stepOnce_) {
    stepOnce_ = false;
    try {
      live_->advance();
      stages = live_->simulationTimes();
    } catch (const sim::WatchdogError& e) {
      say(std::string("the simulation diverged (") + e.what() + "); reset", true);
      live_->reset();
    }
  }
  const std::vector<gpu::StageTime> frameStages = renderViews();
  stages.insert(stages.end(), frameStages.begin(), frameStages.end());
  if (screenshotRequested_) {
    screenshotRequested_ = false;
    screenshot(nextScreenshotPath());
  }
  if (recording_) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.png", recordedFrames_++);
    io::writePng(*recording_ / name, display_->download(), io::ByteEncoding::Linear);
  }
  imgui_->beginFrame();
  drawPanel();
  if (showHelp_) drawHelp();
  if (windowShot_) presenter_->requestCapture();
  const bool presented =
      presenter_->present(display_->image(), [&](VkCommandBuffer commands) { imgui_->render(commands); });
  if (windowShot_) {
    if (std::optional<io::Image> window = presenter_->takeCapture()) {
      io::writePng(*windowShot_, *window, io::ByteEncoding::Linear);
      say("screenshot of the window " + windowShot_->string());
      windowShot_.reset();
    }
  }
  if (!presented) {
    imgui_->swapchainChanged(*presenter_);
    display_ = std::make_unique<DisplayPass>(*context_, *cache_, presenter_->extent().width,
                                             presenter_->extent().height, presenter_->format());
  }
  const auto now = std::chrono::steady_clock::now();
  history_.add(sortStages(stages), std::chrono::duration<float>(now - lastFrame_).count());
  lastFrame_ = now;
}

std::vector<gpu::StageTime> Demo::renderViews() {
  const Camera camera = camera_.view();
  std::vector<gpu::StageTime> stages;
  std::vector<Panel> panels;
  const auto renderMode = [&](modes::RenderMode mode) {
    LiveFrame f = live_->render(mode, camera, lights_, shadows_);
    stages.insert(stages.end(), f.stages.begin(), f.stages.end());
    return f;
  };
  try {
    if (split_) {
      const LiveFrame neural = renderMode(modes::RenderMode::Neural);
      const LiveFrame reference = renderMode(modes::RenderMode::Reference);
      panels = {{neural.color}, {reference.color}};
      const metrics::ImageError error =
          metrics::compareImages(downloadFrame(*neural.color), downloadFrame(*reference.color));
      splitPsnr_ = metrics::psnrDb(error.mseMasked());
    } else {
      const LiveFrame f = renderMode(mode_);
      if (view_ == ViewKind::Frame) panels = {{f.color}};
      if (view_ == ViewKind::Guide) panels = {{f.guide, PanelKind::Guide}};
      if (view_ == ViewKind::Channel) {
        const auto [inB, component] = packedChannel(channel_);
        panels = {{inB ? f.lightmapB : f.lightmapA, PanelKind::Channel, component, component < 3}};
      }
    }
  } catch (const io::InputError& e) {  // neural mode without weights: fall back once to reference
    if (mode_ == modes::RenderMode::Reference && !split_) throw;
    say(e.what(), true);
    split_ = false;
    mode_ = modes::RenderMode::Reference;
    return renderViews();
  }
  display_->draw(panels, exposure_);
  return stages;
}

}  // namespace sixway::app::demo
