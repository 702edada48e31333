#include "modes/flipbook_lightmaps.h"

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <span>
#include <vector>

namespace sixway::modes {
namespace {

// The rectangle baked from `baked` (at the volume centre's depth there) kept at the same world size and
// offset, facing `camera`: a camera-facing sprite, as engines draw flipbooks.
render::ImagePlane facingBillboard(const render::Camera& camera, const render::Camera& baked,
                                   const render::ImagePlane& bakedPlane, glm::vec3 centre) {
  const auto project = [&](const render::Camera& c) {
    const glm::vec3 v = centre - c.position;
    const float z = glm::dot(v, c.forward);
    return std::pair(glm::vec2(glm::dot(v, c.right), glm::dot(v, c.up)) / z, z);
  };
  const auto [bakedCentre, bakedDepth] = project(baked);
  const auto [centreNow, depthNow] = project(camera);
  const float scale = bakedDepth / depthNow;
  return {centreNow + (bakedPlane.min - bakedCentre) * scale,
          centreNow + (bakedPlane.max - bakedCentre) * scale};
}

}  // namespace

FlipbookLightmaps::FlipbookLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                                     const scene::Scene& scene, reference::Scattering scattering,
                                     const reference::MultipleScattering& multiple)
    : BakedLightmaps(context, cache, scene, scattering, multiple, runtime::FrameStages::AllButGuide) {}

render::ImagePlane FlipbookLightmaps::update(runtime::RealtimeFrame& frame,
                                             const runtime::SourceFrame& current) {
  if (!bakedView_) bakedView_.emplace(current.camera, current.billboard);
  bake(frame, current, bakedView_->first, bakedView_->second);
  const render::Camera& camera = current.camera;
  const render::Box volumeBox = current.volume.grid.bounds();
  const render::ImagePlane billboard =
      facingBillboard(camera, bakedView_->first, bakedView_->second, volumeBox.centre());
  // A flipbook knows no depth but its quad's: the shell is the billboard plane through the volume centre.
  const render::DepthRange shellRange = render::boxDepthRange(camera, volumeBox);
  const float planeDepth = glm::dot(volumeBox.centre() - camera.position, camera.forward);
  const float encoded = (planeDepth - shellRange.near) / (shellRange.far - shellRange.near);
  // Against obstacles the card fades over the volume's depth, as soft particles do: an opacity of 1 building
  // up evenly over the box's depth range (the guide's alpha 1, the opacity levels at their share of the
  // range).
  const uint32_t size = frame.lightmapSize();
  std::vector<uint16_t> flat(size_t(size) * size * 4, 0);
  for (size_t i = 0; i < flat.size(); i += 4) {
    flat[i + 1] = glm::packHalf1x16(1.0f);
    flat[i + 2] = glm::packHalf1x16(glm::clamp(encoded, 0.0f, 1.0f));
  }
  frame.guide().upload(std::as_bytes(std::span(flat)));
  constexpr float kLevels[4] = {0.1f, 0.35f, 0.6f, 0.85f};  // shaders/common/depth.glsl, kOpacityLevels
  std::vector<uint16_t> levels(size_t(size) * size * 4);
  for (size_t i = 0; i < levels.size(); ++i) levels[i] = glm::packHalf1x16(kLevels[i % 4]);
  frame.guiding().opacityDepths().upload(std::as_bytes(std::span(levels)));
  return billboard;
}

}  // namespace sixway::modes
