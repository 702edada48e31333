#pragma once
// `sixway-demo`: the window in which the smoke simulates, is lit by neural lightmaps and reacts to the user.
// One loop: input (mouse, keys, the panel or a script) → the simulation's next frame → the real-time frame in
// the chosen mode from the user's camera and lights → the display image → the panel on top → present.
// Everything the user can do is an action of this class, so a script drives exactly what a person does.
// docs/demo.md.
#include <sixway/device.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/demo/demo_script.h"
#include "app/demo/orbit_camera.h"
#include "app/demo/stage_timings.h"
#include "gpu/context.h"
#include "modes/render_mode.h"
#include "scene/scene.h"

struct GLFWwindow;

namespace sixway::gpu {
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app::demo {

class DisplayPass;
class ImGuiLayer;
class LiveScene;
class Presenter;
class Window;

struct DemoOptions {
  std::filesystem::path scene;
  std::filesystem::path weights;
  std::filesystem::path screenshots = "out/screenshots";  // screenshot key and record toggle write here
  std::optional<std::filesystem::path> script;
  bool fp16 = false;
  bool vsync = true;
  int width = 1280, height = 720;
  DeviceOptions device;
};

// What the display shows of the chosen mode.
enum class ViewKind { Frame, Guide, Channel };

class Demo {
 public:
  // Opens the window and loads the scene. Throws io::InputError for a bad scene, script or weights file and
  // std::runtime_error (one line) when there is no display or Vulkan device.
  explicit Demo(const DemoOptions& options);
  ~Demo();

  // Runs until the window closes or the script says quit; returns the exit code (1 when a script command
  // failed or a validation message appeared).
  int run();

  // The actions.
  void orbit(float yawDegrees, float pitchDegrees) { camera_.orbit(yawDegrees, pitchDegrees); }
  void zoom(float factor) { camera_.zoom(factor); }
  void pan(float right, float up) { camera_.pan(right, up); }
  void setMode(modes::RenderMode mode);
  void setView(ViewKind view, int channel = 0);
  void setSplit(bool split);
  void setShadows(bool shadows) { shadows_ = shadows; }
  void addLight(const scene::Light& light);
  void removeLight(size_t light);
  // A point light's position, a directional light's direction (toward the light).
  void placeLight(size_t light, glm::vec3 vector);
  void dragObstacle(size_t obstacle, glm::vec3 target);
  void setPaused(bool paused) { paused_ = paused; }
  void step() { stepOnce_ = true; }
  void reset();
  void setInletStrength(float strength);
  void loadScene(const std::filesystem::path& path);
  // Writes the display image (without the panel) to `path`; refuses to overwrite a file.
  void screenshot(const std::filesystem::path& path);
  // The same with the panel, as the window shows it, after the next frame.
  void windowScreenshot(const std::filesystem::path& path);
  void startRecording(const std::filesystem::path& directory);
  void stopRecording();

 private:
  void runScriptCommand(const ScriptCommand& command);
  void installInput();
  void frame();
  // Renders what the display shows into it; the frame's stage times.
  std::vector<gpu::StageTime> renderViews();
  void drawPanel();
  void drawHelp();
  void say(std::string message, bool error = false);
  size_t lightIndex(float value) const;
  std::filesystem::path nextScreenshotPath() const;
  std::filesystem::path nextRecordingPath() const;

  // Input callbacks (GLFW), through the window's user pointer.
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
  static void onCursor(GLFWwindow* window, double x, double y);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  void dragSelection(float dxPixels, float dyPixels);

  DemoOptions options_;
  std::unique_ptr<Window> window_;
  std::unique_ptr<gpu::Context> context_;
  std::unique_ptr<gpu::PipelineCache> cache_;
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<ImGuiLayer> imgui_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<LiveScene> live_;
  std::optional<ScriptRunner> script_;
  std::filesystem::path scenePath_;

  OrbitCamera camera_;
  std::vector<scene::Light> lights_;
  modes::RenderMode mode_ = modes::RenderMode::Neural;
  ViewKind view_ = ViewKind::Frame;
  int channel_ = 0;  // sixWayChannelNames() index for ViewKind::Channel
  bool split_ = false, shadows_ = true, paused_ = false, stepOnce_ = false, vsync_ = true;
  bool showHelp_ = true;
  float exposure_ = 1.0f;
  size_t selectedObstacle_ = 0, selectedLight_ = 0;
  std::optional<double> splitPsnr_;

  std::optional<std::filesystem::path> recording_;
  int recordedFrames_ = 0;
  bool screenshotRequested_ = false;
  std::optional<std::filesystem::path> windowShot_;
  StageHistory history_;
  std::chrono::steady_clock::time_point lastFrame_;
  std::string status_;
  bool statusIsError_ = false;
  int failures_ = 0;  // script commands that failed
  bool quit_ = false;

  // Mouse state between callbacks.
  bool orbiting_ = false, panning_ = false, draggingObstacle_ = false, draggingLight_ = false;
  double mouseX_ = 0, mouseY_ = 0;
  glm::vec3 dragTarget_{0.0f};  // where the dragged obstacle is headed
};

}  // namespace sixway::app::demo
