#include "app/demo/imgui_layer.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <array>

#include "app/demo/presenter.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/one_shot.h"

namespace sixway::app::demo {
namespace {

void checkResult(VkResult result) {
  sixway::gpu::throwOnFailure(result, "ImGui Vulkan backend");
}

}  // namespace

ImGuiLayer::ImGuiLayer(const gpu::Context& context, GLFWwindow* window, const Presenter& presenter)
    : context_(context) {
  // The backend allocates one combined image sampler set (the font atlas) and frees none.
  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 16;
  poolInfo.poolSizeCount = uint32_t(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  SIXWAY_VK(vkCreateDescriptorPool(context.device(), &poolInfo, nullptr, &pool_));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written into the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context.instance();
  info.PhysicalDevice = context.physicalDevice();
  info.Device = context.device();
  info.QueueFamily = context.queueFamily();
  info.Queue = context.queue();
  info.DescriptorPool = pool_;
  info.MinImageCount = presenter.minImageCount();
  info.ImageCount = presenter.imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkResult;
  ImGui_ImplVulkan_Init(&info, presenter.renderPass());
  gpu::submitOnce(context, [](VkCommandBuffer commands) { ImGui_ImplVulkan_CreateFontsTexture(commands); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
  vkDeviceWaitIdle(context_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(context_.device(), pool_, nullptr);
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::render(VkCommandBuffer commands) {
  ImGui::Render();
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), commands);
}

void ImGuiLayer::swapchainChanged(const Presenter& presenter) {
  ImGui_ImplVulkan_SetMinImageCount(presenter.minImageCount());
}

bool ImGuiLayer::wantsMouse() const {
  return ImGui::GetIO().WantCaptureMouse;
}

bool ImGuiLayer::wantsKeyboard() const {
  return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace sixway::app::demo
