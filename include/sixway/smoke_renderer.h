#pragma once
// The real-time frame of docs/real-time-rendering.md for a SmokeSimulation: the guiding map, the network's
// six-way lightmaps, the obstacles' shadow maps, and six-way billboard shading "over" a colour target, depth
// tested against its depth buffer. Into sixway's own image (tools, tests), or into an engine's images from
// its command buffer (docs/embedding.md).
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sixway/light.h"
#include "sixway/stage_time.h"

namespace sixway {

namespace runtime {
struct Access;
}  // namespace runtime

class Device;
class SmokeRenderer;
class SmokeSimulation;

// A look-at perspective camera over the whole target. An engine target's depth buffer must then hold the
// depth of the standard Vulkan projection with these near and far planes (0 at near, 1 at far, e.g.
// glm::perspectiveRH_ZO); engines with other conventions pass their matrices (setViewProjection).
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDegrees = 45.0f;
  float near = 0.05f, far = 100.0f;
};

// An engine's render target fixed for the renderer's life, in VK_IMAGE_LAYOUT_GENERAL while sixway records
// (and left so): record(commands, frame) draws into it as FrameTargets with GENERAL layouts would. The colour
// image needs COLOR_ATTACHMENT usage; the depth image SAMPLED usage, a depth format (D16_UNORM,
// X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT, D32_SFLOAT, D32_SFLOAT_S8_UINT) and a view of its depth aspect:
// the smoke is drawn over the colour and hidden where the depth buffer is nearer than the smoke.
struct RenderTarget {
  VkImage colorImage = VK_NULL_HANDLE;
  VkImageView colorView = VK_NULL_HANDLE;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;
  VkImage depthImage = VK_NULL_HANDLE;
  VkImageView depthView = VK_NULL_HANDLE;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

// One engine image as a record() finds it and is to leave it: its mip level 0 and array layer 0 (the view
// must show them), in `layout` when the command buffer reaches sixway's composite, moved by sixway to
// VK_IMAGE_LAYOUT_GENERAL for it and then to `finalLayout` (docs/embedding.md, "Targets and layouts"). Both
// GENERAL: no layout change, the engine's barriers stand. Neither may be UNDEFINED or PREINITIALIZED (the
// smoke is drawn over the colour and tested against the depth), nor depth-only for a format with stencil.
struct TargetImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
  VkImageLayout finalLayout = VK_IMAGE_LAYOUT_GENERAL;
};

// The engine's images of one frame: colour (COLOR_ATTACHMENT usage, the format the renderer was made for)
// and depth (SAMPLED usage, D16, X8D24, D24S8, D32 or D32S8, a view of its depth aspect), both width ×
// height, any size from frame to frame; `viewport`: the rectangle the engine's camera renders into (its
// VkViewport, which the projection of setViewProjection maps onto; all zero: the whole image). The smoke is
// drawn inside the viewport only.
struct FrameTargets {
  TargetImage color, depth;
  uint32_t width = 0, height = 0;
  VkRect2D viewport{};
};

// The engine's dynamic rendering that recordComposite draws in: its attachments' formats, as in its
// VkRenderingInfo (or a secondary command buffer's VkCommandBufferInheritanceRenderingInfo), one sample, no
// multiview. The smoke goes "over" colour attachment 0; no other attachment, depth or stencil is written
// (more than one colour attachment needs the device's independentBlend, an Error otherwise).
struct RenderingFormats {
  std::vector<VkFormat> colors;
  VkFormat depth = VK_FORMAT_UNDEFINED;  // UNDEFINED: no depth attachment
  VkFormat stencil = VK_FORMAT_UNDEFINED;
};

// What a composite inside the engine's rendering reads: the engine's depth buffer (SAMPLED usage, a view of
// its depth aspect; D16, X8D24, D24S8, D32 or D32S8) in `depthLayout`, the layout it is in there (when it is
// that rendering's depth attachment too: a read-only depth layout or GENERAL, with the engine's depth writes
// off); the rendering's width × height and the camera's viewport in it (all zero: the whole).
struct CompositeTargets {
  VkImage depth = VK_NULL_HANDLE;
  VkImageView depthView = VK_NULL_HANDLE;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkImageLayout depthLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  uint32_t width = 0, height = 0;
  VkRect2D viewport{};
};

// How lightmaps() packs the eight channels into its two textures (docs/formats.md, "Packing presets"):
// Unity's A = (right, top, back, alpha), B = (left, bottom, front, emissive), the network's own; RLT =
// (right, left, top, alpha), BBF = (bottom, back, front, emissive); O3DE's TLRB = (top, left, right,
// bottom), FB = (front, back, emissive, alpha). Other than Unity's costs a pass ("repack") per frame.
enum class LightmapPacking { Unity, RltBbf, O3de };

// The last frame's six-way lightmaps and where they go (docs/embedding.md, "A frame", lightmaps only): two
// images in the renderer's LightmapPacking (`a` the first texture, `b` the second;
// docs/conventions.md, "Channels and packing"), sampled, in VK_IMAGE_LAYOUT_GENERAL, written by
// the frame's recorded work (a full barrier after it); and the camera-facing quad they cover, in the world,
// at the middle of the smoke's depth: texel row 0 along its top edge. The images and views live as long as
// the renderer; the corners change with the camera and the smoke.
struct LightmapTextures {
  VkImage a = VK_NULL_HANDLE, b = VK_NULL_HANDLE;
  VkImageView viewA = VK_NULL_HANDLE, viewB = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;  // VK_FORMAT_R16G16B16A16_SFLOAT
  uint32_t width = 0, height = 0;
  std::array<glm::vec3, 4> corners{};  // bottom-left, bottom-right, top-right, top-left
};

struct RendererOptions {
  std::filesystem::path weights;  // the network (weights/*.safetensors); an Error names a missing one
  // The weights file's bytes, read during construction instead of `weights` (which then only names them in
  // errors): for engines that pack their files.
  std::span<const std::byte> weightsData;
  // Runs that renderer's network instead (no weights read, nothing allocated for it: docs/embedding.md,
  // "Several instances"): the scenes' lightmap sizes and emission must agree, fp16 is that network's, and
  // the renderers sharing it record into one queue from one thread. The network lives as long as any of them.
  const SmokeRenderer* shareNetwork = nullptr;
  bool fp16 = false;                                 // fp16 feature maps where the device has 16-bit storage
  bool shadows = true;                               // obstacles shadow the smoke
  LightmapPacking packing = LightmapPacking::Unity;  // of lightmaps()
  // Shadow-atlas tiles: the most lights that cast shadows at once (a note names a light beyond them).
  // Unset: one per shadow-casting light of the scene; set it when setLights() may add more.
  std::optional<uint32_t> shadowedLights;
};

class SmokeRenderer {
 public:
  // Renders into an image of its own, the scene's render size, over the scene's background and obstacles.
  SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options);
  // Renders into the engine's target; the engine draws its scene (and the obstacles) itself.
  SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                const RenderTarget& target);
  // Renders into the engine's images of each frame (record with FrameTargets), whose colour format is
  // `colorFormat` (the shading's pipeline is made for it).
  SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                VkFormat colorFormat);
  // Draws inside the engine's own dynamic rendering of these formats: each frame recordLightmaps, then
  // recordComposite (docs/embedding.md, "Inside the engine's rendering").
  SmokeRenderer(Device& device, SmokeSimulation& simulation, const RendererOptions& options,
                const RenderingFormats& rendering);
  ~SmokeRenderer();
  SmokeRenderer(const SmokeRenderer&) = delete;
  SmokeRenderer& operator=(const SmokeRenderer&) = delete;

  // The camera from now on; until set, the scene's camera (on its path).
  void setCamera(const Camera& camera);
  // The camera from now on as the engine's shaders have it (docs/embedding.md, "The camera"). `view`:
  // world → view space, a rotation and a translation (right- or left-handed). `projection`: a perspective
  // into Vulkan's clip space (w = ±z_view) for a viewport of positive height (NDC y = −1 at the target's top
  // row), in any depth convention (standard, reversed-Z, infinite far plane), with this frame's TAA jitter
  // in its z column. An engine target's depth buffer must hold this projection's depth. Throws
  // std::invalid_argument for a view that is not rigid or a projection that is not such a perspective.
  void setViewProjection(const glm::mat4& view, const glm::mat4& projection);
  // The lights from now on, at most maxLights() (the shading blends the lightmaps once per light); until
  // set, the scene's lights (on their paths). std::invalid_argument for more, for a negative or non-finite
  // colour or intensity, or a directional light without a direction.
  void setLights(const std::vector<Light>& lights);
  uint32_t maxLights() const;

  // Own image: renders the simulation's current smoke and waits.
  void render();
  // Engine target: records the frame into `commands` (primary, recording, outside a render pass), as
  // frame number `frame`, after SmokeSimulation::record of the same frame. Nothing waits.
  void record(VkCommandBuffer commands, uint64_t frame);
  // The same into this frame's `targets`, with the layout changes they ask for. A target not among the last
  // framesInFlight + 1 (at least four) recorded, or of a new size or viewport, costs one recording of the
  // composite on the host (docs/embedding.md, "Targets and layouts"). std::invalid_argument for targets that
  // do not fit.
  void record(VkCommandBuffer commands, uint64_t frame, const FrameTargets& targets);
  // The RenderingFormats renderer's frame in two parts. First, into a primary command buffer outside any
  // render pass, after SmokeSimulation::record: shadow maps, guide, network and the composite's values for
  // this frame's `targets`, between full barriers. Then recordComposite, into the command buffer (primary,
  // or secondary with RENDER_PASS_CONTINUE) that is inside the engine's rendering at that point of the
  // queue: one draw (pipeline, push descriptors, push constants, viewport, scissor: the engine rebinds its
  // own after it) between two timestamps (the "shade" stage time), no barrier. The engine's barrier into the
  // depth layout must make its depth writes visible to fragment-shader reads. std::invalid_argument for
  // targets that do not fit, or recordComposite before any recordLightmaps.
  void recordLightmaps(VkCommandBuffer commands, uint64_t frame, const CompositeTargets& targets);
  void recordComposite(VkCommandBuffer commands) const;
  // Forgets the recordings of the targets passed so far: call it when the engine destroys images it passed
  // (after the GPU finished the frames that used them, as destroying them requires), before new images that
  // may reuse their handles are passed.
  void forgetTargets();

  // GPU time per stage of the latest frame whose times are in (a frame or more late with an engine).
  std::vector<StageTime> stageTimes() const;
  // What the last frame could not do as asked, for the user, each said once (e.g. a shadow-casting light
  // beyond shadowedLights, drawn unshadowed).
  std::vector<std::string> notes() const;
  // Own image: the last frame, RGBA floats (linear, premultiplied), row 0 at the top.
  std::vector<float> image() const;
  // The camera's image in pixels: the own image's or the engine target's, the last record's viewport.
  uint32_t width() const;
  uint32_t height() const;
  // The six-way lightmaps of the last frame, for engines that shade the billboard themselves.
  LightmapTextures lightmaps() const;

 private:
  friend runtime::Access;  // sixway's own tools (src/runtime/internal.h, not installed)
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixway
