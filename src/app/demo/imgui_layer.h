#pragma once
// Dear ImGui (Debian's libimgui-dev, its GLFW and Vulkan backends) drawn into the presenter's render pass.
#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace sixway::gpu {
class Context;
}

namespace sixway::app::demo {

class Presenter;

class ImGuiLayer {
 public:
  // Installs ImGui's GLFW callbacks after the window's own (it chains to them).
  ImGuiLayer(const gpu::Context& context, GLFWwindow* window, const Presenter& presenter);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  void beginFrame();
  // Ends the frame and records its draw data into `commands` (inside the render pass).
  void render(VkCommandBuffer commands);
  // After the swapchain was recreated.
  void swapchainChanged(const Presenter& presenter);
  // Whether ImGui wants the mouse or the keyboard this frame (then the scene ignores them).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  const gpu::Context& context_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
};

}  // namespace sixway::app::demo
