#pragma once
// GLFW for the demo: the library's lifetime and one resizable window without a client API (Vulkan draws it).
#include <string>
#include <vector>

struct GLFWwindow;

namespace sixway::app::demo {

class Window {
 public:
  // Throws std::runtime_error (one line) when there is no display or the Vulkan loader cannot present.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  // The Vulkan instance extensions the window system needs (for gpu::ContextOptions).
  static std::vector<std::string> requiredInstanceExtensions();
  bool shouldClose() const;
  void requestClose();
  void setTitle(const std::string& title);
  // Asks the window system for a new size (the swapchain follows on the next frame).
  void resize(int width, int height);

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace sixway::app::demo
