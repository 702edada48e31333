#include "reference/fitted_lightmaps.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "io/error.h"
#include "render/sixway.h"

namespace sixway::reference {
namespace {

void addStages(std::vector<gpu::StageTime>& total, const std::vector<gpu::StageTime>& bake) {
  for (const gpu::StageTime& t : bake) {
    auto same =
        std::find_if(total.begin(), total.end(), [&](const gpu::StageTime& s) { return s.name == t.name; });
    if (same == total.end())
      total.push_back(t);
    else
      same->milliseconds += t.milliseconds;
  }
}

std::vector<glm::vec3> checked(std::vector<glm::vec3> directions) {
  if (directions.empty() || directions.size() % render::kSixWayLights != 0 || directions.size() > 96)
    throw std::invalid_argument("FittedLightmaps: " + std::to_string(directions.size()) +
                                " directions, not a multiple of 6 in 6..96");
  return directions;
}

}  // namespace

std::vector<glm::vec3> fitDirections(int count) {
  if (count % render::kSixWayLights != 0 || count < 12 || count > 96)
    throw io::InputError("reference-fit", "the light directions must be a multiple of 6 in 12..96 (got " +
                                              std::to_string(count) + ")");
  return sphereDirections(count);
}

FittedLightmaps::FittedLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                                 std::vector<glm::vec3> directions)
    : baker_(context, cache), fit_(checked(std::move(directions))) {}

io::Image FittedLightmaps::bake(const render::Volume& volume, const scene::Smoke& smoke,
                                const render::Camera& camera, const render::ImagePlane& billboard,
                                const BakeSettings& settings, const MultipleScattering& multiple) {
  if (settings.lights) throw std::invalid_argument("FittedLightmaps::bake: the lights are the fit's");
  const std::vector<glm::vec3>& directions = fit_.directions();
  const size_t texels = size_t(settings.width) * size_t(settings.height), count = directions.size();
  std::vector<float> values(texels * count);  // per texel, its value under each direction
  io::Image fitted;
  stages_.clear();
  for (size_t first = 0; first < count; first += render::kSixWayLights) {
    BakeSettings group = settings;
    group.lights.emplace();
    for (int i = 0; i < render::kSixWayLights; ++i) {
      const glm::vec3 d = directions[first + i];
      (*group.lights)[i] = d.x * camera.right + d.y * camera.up + d.z * camera.forward;
    }
    MultipleScattering traced = multiple;
    traced.seed = multiple.seed + uint32_t(first / render::kSixWayLights) * 0x9E3779B9u;  // independent noise
    const io::Image image =
        baker_.bake(volume, smoke, camera, billboard, group, Scattering::Multiple, traced);
    addStages(stages_, baker_.stageTimes());
    for (size_t p = 0; p < texels; ++p)
      for (int i = 0; i < render::kSixWayLights; ++i)
        values[p * count + first + i] = image.pixels[p * render::kSixWayChannels + i];
    if (first == 0) fitted = image;  // its alpha and emissive
  }
  for (size_t p = 0; p < texels; ++p) {
    const std::array<float, 6> maps = fit_.fit(std::span(values).subspan(p * count, count));
    for (int i = 0; i < render::kSixWayLights; ++i) fitted.pixels[p * render::kSixWayChannels + i] = maps[i];
  }
  return fitted;
}

}  // namespace sixway::reference
