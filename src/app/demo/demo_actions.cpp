// The demo's actions, and the script commands that call them (docs/demo.md, "Scripts").
#include <algorithm>
#include <cctype>
#include <glm/geometric.hpp>

#include "app/demo/demo_app.h"
#include "app/demo/display_pass.h"
#include "app/demo/live_scene.h"
#include "app/demo/window.h"
#include "io/error.h"
#include "io/png.h"
#include "render/sixway.h"

namespace sixway::app::demo {

namespace fs = std::filesystem;

void Demo::setMode(modes::RenderMode mode) {
  if (mode == modes::RenderMode::PathTrace)
    throw std::invalid_argument("the path tracer is not interactive: use `sixway render --mode pathtrace`");
  mode_ = mode;
  split_ = false;
}

void Demo::setView(ViewKind view, int channel) {
  if (channel < 0 || channel >= render::kSixWayChannels)
    throw std::invalid_argument("no lightmap channel " + std::to_string(channel));
  view_ = view;
  channel_ = channel;
}

void Demo::setSplit(bool split) {
  split_ = split;
  if (!split) splitPsnr_.reset();
}

void Demo::addLight(const scene::Light& light) {
  if (lights_.size() >= kMaxDemoLights)
    throw std::invalid_argument("at most " + std::to_string(kMaxDemoLights) + " lights");
  lights_.push_back(light);
  selectedLight_ = lights_.size() - 1;
}

void Demo::removeLight(size_t light) {
  if (light >= lights_.size()) throw std::invalid_argument("no light " + std::to_string(light));
  lights_.erase(lights_.begin() + std::ptrdiff_t(light));
  selectedLight_ = lights_.empty() ? 0 : std::min(selectedLight_, lights_.size() - 1);
}

void Demo::placeLight(size_t light, glm::vec3 vector) {
  if (light >= lights_.size()) throw std::invalid_argument("no light " + std::to_string(light));
  if (auto* point = std::get_if<scene::PointLight>(&lights_[light].source)) {
    point->position = vector;
  } else {
    if (glm::length(vector) <= 0.0f) throw std::invalid_argument("a light direction must not be zero");
    std::get<scene::DirectionalLight>(lights_[light].source).direction = glm::normalize(vector);
  }
}

void Demo::dragObstacle(size_t obstacle, glm::vec3 target) {
  if (obstacle >= live_->obstacleCount())
    throw std::invalid_argument("no obstacle " + std::to_string(obstacle));
  live_->steerObstacle(obstacle, target);
  selectedObstacle_ = obstacle;
}

void Demo::reset() {
  live_->reset();
  history_ = StageHistory();
}

void Demo::setInletStrength(float strength) {
  if (strength < 0.0f || strength > live_->maxInletStrength())
    throw std::invalid_argument("inlet strength outside [0, " + std::to_string(live_->maxInletStrength()) +
                                "]");
  live_->setInletStrength(strength);
}

void Demo::loadScene(const fs::path& path) {
  const scene::Scene scene = scene::loadScene(path);  // throws before anything changes
  live_.reset();                                      // one scene's GPU memory at a time
  live_ = std::make_unique<LiveScene>(*context_, *cache_, path,
                                      LiveSceneOptions{options_.weights, options_.fp16});
  scenePath_ = path;
  camera_ = OrbitCamera::fromScene(scene.camera);
  lights_ = startingLights(scene);
  selectedObstacle_ = selectedLight_ = 0;
  history_ = StageHistory();
  say("scene " + path.string());
}

void Demo::screenshot(const fs::path& path) {
  if (fs::exists(path)) throw io::InputError(path.string(), "exists already; screenshots never overwrite");
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  io::writePng(path, display_->download(), io::ByteEncoding::Linear);  // the display holds sRGB codes
  say("screenshot " + path.string());
}

void Demo::windowScreenshot(const fs::path& path) {
  if (fs::exists(path)) throw io::InputError(path.string(), "exists already; screenshots never overwrite");
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  windowShot_ = path;
}

void Demo::startRecording(const fs::path& directory) {
  if (fs::exists(directory) && !fs::is_empty(directory))
    throw io::InputError(directory.string(), "is not empty; recordings never overwrite");
  fs::create_directories(directory);
  recording_ = directory;
  recordedFrames_ = 0;
  say("recording into " + directory.string());
}

void Demo::stopRecording() {
  if (recording_) say("recorded " + std::to_string(recordedFrames_) + " frames into " + recording_->string());
  recording_.reset();
}

fs::path Demo::nextScreenshotPath() const {
  for (int i = 0;; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "sixway_%04d.png", i);
    if (!fs::exists(options_.screenshots / name)) return options_.screenshots / name;
  }
}

fs::path Demo::nextRecordingPath() const {
  for (int i = 0;; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "recording_%03d", i);
    if (!fs::exists(options_.screenshots / name)) return options_.screenshots / name;
  }
}

size_t Demo::lightIndex(float value) const {
  if (value < 0.0f || value != float(int(value)) || size_t(value) >= lights_.size())
    throw std::invalid_argument("no light " + std::to_string(value) + " (there are " +
                                std::to_string(lights_.size()) + ")");
  return size_t(value);
}

void Demo::runScriptCommand(const ScriptCommand& c) {
  const auto on = [&] { return c.words.at(0) == "on"; };
  const auto vec = [&](size_t first) {
    return glm::vec3(c.number(first), c.number(first + 1), c.number(first + 2));
  };
  if (c.name == "orbit") {
    orbit(c.number(0), c.number(1));
  } else if (c.name == "zoom") {
    if (c.number(0) <= 0.0f) throw std::invalid_argument("zoom needs a factor > 0");
    zoom(c.number(0));
  } else if (c.name == "pan") {
    pan(c.number(0), c.number(1));
  } else if (c.name == "mode") {
    setMode(modes::parseRenderMode(c.words[0]));
  } else if (c.name == "view") {
    const auto& names = render::sixWayChannelNames();
    const auto lower = [](std::string text) {
      for (char& ch : text) ch = char(std::tolower(static_cast<unsigned char>(ch)));
      return text;
    };
    const auto channel = std::find_if(names.begin(), names.end(), [&](const std::string& name) {
      return lower(name) == lower(c.words[0]);
    });
    if (c.words[0] == "frame")
      setView(ViewKind::Frame);
    else if (c.words[0] == "guide")
      setView(ViewKind::Guide);
    else if (channel != names.end())
      setView(ViewKind::Channel, int(channel - names.begin()));
    else
      throw std::invalid_argument("view " + c.words[0] + ": expected frame, guide or a lightmap channel");
  } else if (c.name == "split") {
    setSplit(on());
  } else if (c.name == "shadows") {
    setShadows(on());
  } else if (c.name == "light") {
    const std::string& verb = c.words[0];
    if (verb == "add") {
      scene::Light light;
      if (c.words[1] == "point")
        light.source = scene::PointLight{vec(2)};
      else
        light.source = scene::DirectionalLight{glm::normalize(vec(2))};
      addLight(light);
    } else if (verb == "move") {
      placeLight(lightIndex(c.number(1)), vec(2));
    } else if (verb == "color") {
      lights_[lightIndex(c.number(1))].color = glm::max(vec(2), glm::vec3(0.0f));
    } else if (verb == "intensity") {
      lights_[lightIndex(c.number(1))].intensity = std::max(c.number(2), 0.0f);
    } else {
      removeLight(lightIndex(c.number(1)));
    }
  } else if (c.name == "obstacle") {
    dragObstacle(size_t(std::max(c.number(0), 0.0f)), vec(1));
  } else if (c.name == "pause") {
    setPaused(true);
  } else if (c.name == "resume") {
    setPaused(false);
  } else if (c.name == "step") {
    step();
  } else if (c.name == "reset") {
    reset();
  } else if (c.name == "inlet") {
    setInletStrength(c.number(0));
  } else if (c.name == "exposure") {
    exposure_ = std::max(c.number(0), 0.0f);
  } else if (c.name == "vsync") {
    vsync_ = on();
  } else if (c.name == "resize") {
    if (c.number(0) < 64 || c.number(1) < 64) throw std::invalid_argument("a window is at least 64 x 64");
    window_->resize(int(c.number(0)), int(c.number(1)));
  } else if (c.name == "screenshot") {
    if (c.words.size() == 2)
      windowScreenshot(c.words[0]);
    else
      screenshot(c.words[0]);
  } else if (c.name == "record") {
    if (c.words[0] == "stop")
      stopRecording();
    else
      startRecording(c.words[0]);
  } else if (c.name == "scene") {
    loadScene(c.words[0]);
  } else if (c.name == "quit") {
    quit_ = true;
  }
}

}  // namespace sixway::app::demo
