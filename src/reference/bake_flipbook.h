#pragma once
// The traditional six-way workflow: a sequence baked from one fixed view into flipbooks (Unity's packing or a
// preset, EXR + PNG + TGA, JSON sidecar) plus one EXR per frame, with multiple scattering (the default, as
// DCC tools bake) or single scattering (ScatteredLightmaps). The sidecar says which.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gpu/sequence.h"
#include "reference/flipbook.h"
#include "reference/lightmap_baker.h"
#include "reference/scattered_lightmaps.h"
#include "render/camera.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::reference {

struct FlipbookBake {
  std::filesystem::path out;  // an existing, empty directory
  int firstFrame = 0;         // frames [firstFrame, firstFrame + frameCount) of the sequence
  int frameCount = 1;
  int columns = 0;  // 0: a near-square grid
  ChannelPacking packing = unityPacking();
  render::Camera camera;  // fixed for the whole sequence
  scene::Smoke smoke;     // optics
  BakeSettings settings;  // tile size and quadrature
  // settings.lightSpacingCells chosen by lightSpacingFor from the sequence's densest cell, or as given.
  bool lightSpacingFromSmoke = true;
  Scattering scattering = Scattering::Multiple;
  MultipleScattering multiple;  // with Scattering::Multiple; the same seed every frame (coherent noise)
  nlohmann::json provenance;    // added to the sidecar (where the volumes came from, the command)
  // The emissive component as Unity's Single Channel mask (unityEmissiveMask; the default) or as sixway's
  // premultiplied luminance.
  bool emissiveMask = true;
};

struct FlipbookBakeResult {
  std::filesystem::path sidecar;
  FlipbookLayout layout;
  render::ImagePlane billboard;
  std::vector<double> frameMilliseconds;     // GPU time per baked frame
  std::optional<EmissiveMask> emissiveMask;  // as written (none: premultiplied, or no emission)
};

// Bakes the frames one after the other; `progress` gets one line per frame. Throws io::InputError for a frame
// range outside the sequence and a camera that does not see the whole volume box in front of it.
FlipbookBakeResult bakeFlipbook(const gpu::Context& context, const gpu::PipelineCache& cache,
                                render::VolumeSequence& sequence, const FlipbookBake& job,
                                const std::function<void(const std::string&)>& progress);

}  // namespace sixway::reference
