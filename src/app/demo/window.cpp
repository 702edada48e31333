#include "app/demo/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace sixway::app::demo {
namespace {

std::string lastGlfwError() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  if (!glfwInit()) throw std::runtime_error("no display: GLFW cannot start (" + lastGlfwError() + ")");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw std::runtime_error("the Vulkan loader offers no window-system support to GLFW");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string error = lastGlfwError();
    glfwTerminate();
    throw std::runtime_error("cannot open a window: " + error);
  }
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<std::string>(names, names + n);
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(window_);
}

void Window::requestClose() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void Window::resize(int width, int height) {
  glfwSetWindowSize(window_, width, height);
}

void Window::setTitle(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

}  // namespace sixway::app::demo
