// The timings of docs/real-time-rendering.md, "Six-way shading" (not a test): GPU time of the stage "shade"
// (timestamps, median of 21 replays after a warm-up) for a 256² RGBA16F frame whose billboard (128² RGBA16F
// lightmaps and guide) covers the projection of a unit box, with no light, then with 4 lights and L1 ambient,
// then with an obstacle depth buffer and two of the lights shadowed from a 1024² × 2 shadow atlas (PCF
// radius 1.5 texels: 16 fetches), then with 16 lights, all shadowed; the shadowed cases again with opacity
// depths (the smoke composited as a volume, each shadow looked up at three depths). Usage: shading_bench.
#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "render/billboard.h"
#include "render/sixway_shading.h"

namespace {

using namespace sixway;

// D32 or RGBA16F texels uniform in [lo, hi].
gpu::Image filled(const gpu::Context& context, uint32_t width, uint32_t height, VkFormat format, float lo,
                  float hi, std::mt19937& rng, const char* name) {
  gpu::Image image(context, {width, height, 1, format, VK_IMAGE_USAGE_SAMPLED_BIT, name});
  std::uniform_real_distribution<float> value(lo, hi);
  if (format == VK_FORMAT_D32_SFLOAT) {
    std::vector<float> texels(size_t(width) * height);
    for (float& t : texels) t = value(rng);
    image.upload(std::as_bytes(std::span(texels)));
  } else {
    std::vector<Imath::half> texels(size_t(width) * height * 4);
    for (Imath::half& t : texels) t = value(rng);
    image.upload(std::as_bytes(std::span(texels)));
  }
  return image;
}

// RGBA16F opacity depths: per texel four encoded depths in increasing order, some levels not reached (1).
gpu::Image opacityLevels(const gpu::Context& context, uint32_t size, std::mt19937& rng) {
  gpu::Image image(
      context, {size, size, 1, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, "opacity depths"});
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<Imath::half> texels(size_t(size) * size * 4);
  for (size_t t = 0; t < texels.size(); t += 4) {
    std::array<float, 4> levels{value(rng), value(rng), value(rng), value(rng)};
    std::sort(levels.begin(), levels.end());
    for (int k = 0; k < 4; ++k) texels[t + k] = levels[k] > 0.8f ? 1.0f : levels[k];
  }
  image.upload(std::as_bytes(std::span(texels)));
  return image;
}

double medianMs(gpu::Sequence& sequence, render::SixWayShading& shading, const render::Camera& camera,
                const render::ImagePlane& frame, const render::ImagePlane& billboard,
                render::DepthRange range, const std::vector<render::ShadingLight>& lights,
                bool ambient = true) {
  scene::AmbientSh sh;
  sh.coefficients = {glm::vec3(0.2f), glm::vec3(0.05f), glm::vec3(0.1f), glm::vec3(-0.05f)};
  render::ShadingControls controls;
  controls.absorption = true;
  const std::optional<scene::Ambient> environment =
      ambient ? std::optional<scene::Ambient>(sh) : std::nullopt;
  shading.update(camera, frame, billboard, range, render::depthMapping({0.1f, 20.0f}), lights, environment,
                 controls);
  sequence.submit();  // warm-up
  std::vector<double> times;
  for (int i = 0; i < 21; ++i) {
    sequence.submit();
    times.push_back(sequence.stageTimes().front().milliseconds);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

}  // namespace

int main() {
  gpu::Context context;
  gpu::PipelineCache cache(context);
  std::printf("device: %s (%s)\n", context.properties().deviceName, context.driver().driverInfo);
  std::mt19937 rng(1);
  const render::Box box{glm::vec3(-1.0f), glm::vec3(1.0f)};
  const render::Camera camera = render::Camera::lookAt({1.5f, 1.0f, 4.0f}, {0, 0, 0}, {0, 1, 0}, 40.0f);
  const render::ImagePlane frame = render::fullFrame(camera, 256, 256);
  const render::ImagePlane billboard = render::billboardBounds(camera, box, 1.0f);
  const render::DepthRange range = render::boxDepthRange(camera, box);
  const glm::vec2 covered = glm::min(billboard.max, frame.max) - glm::max(billboard.min, frame.min);
  std::printf("billboard: %.0f %% of the frame\n",
              100.0 * covered.x * covered.y / ((frame.max.x - frame.min.x) * (frame.max.y - frame.min.y)));

  const VkFormat half = VK_FORMAT_R16G16B16A16_SFLOAT;
  const gpu::Image a = filled(context, 128, 128, half, 0.0f, 1.0f, rng, "lightmap A");
  const gpu::Image b = filled(context, 128, 128, half, 0.0f, 1.0f, rng, "lightmap B");
  const gpu::Image guide = filled(context, 128, 128, half, 0.0f, 1.0f, rng, "guide");
  const gpu::Image opacityDepths = opacityLevels(context, 128, rng);
  const gpu::Image depth = filled(context, 256, 256, VK_FORMAT_D32_SFLOAT, 0.5f, 1.0f, rng, "obstacle depth");
  const gpu::Image atlas = filled(context, 1024, 2048, VK_FORMAT_D32_SFLOAT, 0.0f, 1.0f, rng, "shadow atlas");
  gpu::Image target(context, {256, 256, 1, half, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "target"});
  const glm::mat4 lightMatrix = glm::mat4(0.4f, 0, 0, 0, 0, 0.4f, 0, 0, 0, 0, 0.1f, 0, 0, 0, 0.5f, 1);

  std::vector<render::ShadingLight> four(4);
  for (int i = 0; i < 4; ++i) {
    four[i].type = i % 2 ? render::ShadingLight::Type::Point : render::ShadingLight::Type::Directional;
    four[i].vector = glm::normalize(glm::vec3(1.0f - i, 1.0f, 0.5f * i)) * (i % 2 ? 3.0f : 1.0f);
    four[i].shadowMatrix = lightMatrix;
  }
  std::vector<render::ShadingLight> fourShadowed = four;
  fourShadowed[0].shadowTile = 0;
  fourShadowed[1].shadowTile = 1;
  std::vector<render::ShadingLight> sixteen(16, fourShadowed[0]);
  for (int i = 0; i < 16; ++i) sixteen[i].shadowTile = i % 2;

  render::SixWayShading shading(context, cache, half, 16);
  gpu::Sequence plain(context), shadowed(context), volume(context);
  shading.record(plain, a, b, &guide, nullptr, nullptr, {}, target);
  shading.record(shadowed, a, b, &guide, nullptr, &depth, {&atlas, 1024, 1.5f, 0.002f}, target);
  shading.record(volume, a, b, &guide, &opacityDepths, &depth, {&atlas, 1024, 1.5f, 0.002f}, target);
  plain.finish();
  shadowed.finish();
  volume.finish();
  std::printf("no lights, no ambient:                      %.3f ms\n",
              medianMs(plain, shading, camera, frame, billboard, range, {}, false));
  std::printf("4 lights, ambient:                          %.3f ms\n",
              medianMs(plain, shading, camera, frame, billboard, range, four));
  std::printf("4 lights (2 shadowed), obstacle depth:      %.3f ms\n",
              medianMs(shadowed, shading, camera, frame, billboard, range, fourShadowed));
  std::printf("16 lights (all shadowed), obstacle depth:   %.3f ms\n",
              medianMs(shadowed, shading, camera, frame, billboard, range, sixteen));
  std::printf("4 lights (2 shadowed), opacity depths:      %.3f ms\n",
              medianMs(volume, shading, camera, frame, billboard, range, fourShadowed));
  std::printf("16 lights (all shadowed), opacity depths:   %.3f ms\n",
              medianMs(volume, shading, camera, frame, billboard, range, sixteen));
  return 0;
}
