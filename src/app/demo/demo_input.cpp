// Mouse and keyboard → the demo's actions (the shortcuts are listed by the help overlay, drawHelp()).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "app/demo/demo_app.h"
#include "app/demo/imgui_layer.h"
#include "app/demo/live_scene.h"
#include "app/demo/window.h"

namespace sixway::app::demo {
namespace {

Demo& demoOf(GLFWwindow* window) {
  return *static_cast<Demo*>(glfwGetWindowUserPointer(window));
}

constexpr float kOrbitDegreesPerPixel = 0.3f;

}  // namespace

void Demo::installInput() {
  GLFWwindow* w = window_->handle();
  glfwSetWindowUserPointer(w, this);
  glfwSetMouseButtonCallback(w, onMouseButton);
  glfwSetCursorPosCallback(w, onCursor);
  glfwSetScrollCallback(w, onScroll);
  glfwSetKeyCallback(w, onKey);
}

void Demo::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Demo& d = demoOf(window);
  if (action == GLFW_RELEASE) {
    d.orbiting_ = d.panning_ = d.draggingObstacle_ = d.draggingLight_ = false;
    return;
  }
  if (d.imgui_ && d.imgui_->wantsMouse()) return;
  glfwGetCursorPos(window, &d.mouseX_, &d.mouseY_);
  if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_CONTROL) && d.live_->obstacleCount() > 0) {
    d.draggingObstacle_ = true;
    d.dragTarget_ = d.live_->obstaclePosition(d.selectedObstacle_);
  } else if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT) &&
             d.selectedLight_ < d.lights_.size() &&
             std::holds_alternative<scene::PointLight>(d.lights_[d.selectedLight_].source)) {
    d.draggingLight_ = true;
  } else if (button == GLFW_MOUSE_BUTTON_LEFT) {
    d.orbiting_ = true;
  } else {
    d.panning_ = true;
  }
}

void Demo::onCursor(GLFWwindow* window, double x, double y) {
  Demo& d = demoOf(window);
  const float dx = float(x - d.mouseX_), dy = float(y - d.mouseY_);
  d.mouseX_ = x;
  d.mouseY_ = y;
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  // The world size of a pixel at unit distance along the view.
  const float pixel = 2.0f * std::tan(glm::radians(d.camera_.fovDeg) / 2.0f) / float(std::max(height, 1));
  try {
    if (d.orbiting_) d.orbit(-dx * kOrbitDegreesPerPixel, dy * kOrbitDegreesPerPixel);
    if (d.panning_) d.pan(-dx * pixel, dy * pixel);
    if (d.draggingObstacle_ || d.draggingLight_) d.dragSelection(dx * pixel, dy * pixel);
  } catch (const std::exception& e) {
    d.say(e.what(), true);
  }
}

// Moves the selected obstacle (or point light) across the view, in the plane through it facing the camera.
void Demo::dragSelection(float right, float down) {
  const render::Camera c = camera_.camera();
  const auto across = [&](glm::vec3 p) {
    const float depth = std::max(glm::dot(p - c.position, c.forward), 1e-3f);
    return depth * (right * c.right - down * c.up);
  };
  if (draggingObstacle_) {
    dragTarget_ += across(dragTarget_);
    dragObstacle(selectedObstacle_, dragTarget_);
  } else {
    auto& point = std::get<scene::PointLight>(lights_[selectedLight_].source);
    point.position += across(point.position);
  }
}

void Demo::onScroll(GLFWwindow* window, double, double dy) {
  Demo& d = demoOf(window);
  if (d.imgui_ && d.imgui_->wantsMouse()) return;
  d.zoom(std::pow(0.9f, float(dy)));
}

void Demo::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  Demo& d = demoOf(window);
  if (action != GLFW_PRESS || (d.imgui_ && d.imgui_->wantsKeyboard())) return;
  try {
    switch (key) {
      case GLFW_KEY_ESCAPE:
        d.quit_ = true;
        break;
      case GLFW_KEY_H:
        d.showHelp_ = !d.showHelp_;
        break;
      case GLFW_KEY_SPACE:
        d.paused_ = !d.paused_;
        break;
      case GLFW_KEY_N:
        d.step();
        break;
      case GLFW_KEY_R:
        d.reset();
        break;
      case GLFW_KEY_1:
        d.setMode(modes::RenderMode::Neural);
        break;
      case GLFW_KEY_2:
        d.setMode(modes::RenderMode::Reference);
        break;
      case GLFW_KEY_3:
        d.setMode(modes::RenderMode::Traditional);
        break;
      case GLFW_KEY_4:
        d.setMode(modes::RenderMode::Guide);
        break;
      case GLFW_KEY_5:
        d.setMode(modes::RenderMode::GuideLit);
        break;
      case GLFW_KEY_F:
        d.setView(ViewKind::Frame);
        break;
      case GLFW_KEY_G:
        d.setView(ViewKind::Guide);
        break;
      case GLFW_KEY_L:
        d.setView(ViewKind::Channel, d.view_ == ViewKind::Channel ? (d.channel_ + 1) % 8 : 0);
        break;
      case GLFW_KEY_C:
        d.setSplit(!d.split_);
        break;
      case GLFW_KEY_S:
        d.shadows_ = !d.shadows_;
        break;
      case GLFW_KEY_V:
        d.vsync_ = !d.vsync_;
        break;
      case GLFW_KEY_P:
        if (mods & GLFW_MOD_SHIFT)
          d.windowScreenshot(d.nextScreenshotPath());
        else
          d.screenshotRequested_ = true;
        break;
      case GLFW_KEY_O:
        d.recording_ ? d.stopRecording() : d.startRecording(d.nextRecordingPath());
        break;
      case GLFW_KEY_A: {
        scene::Light light;
        light.source = scene::PointLight{d.camera_.target + glm::vec3(0.3f, 0.3f, 0.3f)};
        d.addLight(light);
        break;
      }
      case GLFW_KEY_DELETE:
      case GLFW_KEY_BACKSPACE:
        if (!d.lights_.empty()) d.removeLight(d.selectedLight_);
        break;
      case GLFW_KEY_TAB:
        if (d.live_->obstacleCount() > 0)
          d.selectedObstacle_ = (d.selectedObstacle_ + 1) % d.live_->obstacleCount();
        break;
      case GLFW_KEY_RIGHT_BRACKET:
        if (!d.lights_.empty()) d.selectedLight_ = (d.selectedLight_ + 1) % d.lights_.size();
        break;
      case GLFW_KEY_EQUAL:
        d.exposure_ *= 1.25f;
        break;
      case GLFW_KEY_MINUS:
        d.exposure_ /= 1.25f;
        break;
      default:
        break;
    }
  } catch (const std::exception& e) {
    d.say(e.what(), true);
  }
}

}  // namespace sixway::app::demo
