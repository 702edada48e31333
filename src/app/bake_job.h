#pragma once
// What `sixway bake` (bake_command.h) bakes, from its options: the scene (or none for OpenVDB files), the
// smoke's optics, the tile size and frame count, the sequence of volumes with where it came from, and the
// flipbook job itself.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/bake_options.h"
#include "reference/bake_flipbook.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::app {

struct BakeTile {
  int width = 0, height = 0;
};

// The volumes baked and the sidecar's record of them ("source").
struct BakeSource {
  std::unique_ptr<render::VolumeSequence> sequence;
  nlohmann::json provenance;
};

// The scene of --scene, with --voxels for its VDB files; none for --vdb.
std::optional<scene::Scene> bakedScene(const BakeOptions& o);
// The scene's smoke (or the defaults) with the optics options.
scene::Smoke bakedSmoke(const BakeOptions& o, const scene::Scene* scene);
// --tile, else the scene's lightmap size, else 128.
BakeTile bakedTile(const BakeOptions& o, const scene::Scene* scene);
// --frames, else 16 for a simulated scene and every frame from --first for VDB files; refused when the
// flipbook would be too large, before anything is simulated or loaded.
int bakedFrameCount(const BakeOptions& o, const scene::Scene* scene, BakeTile tile);

// The scene's simulation or VDB files, or the --vdb files: what the device cannot hold is an error naming the
// setting to reduce.
BakeSource openBakeSource(const gpu::Context& context, const gpu::PipelineCache& cache, const BakeOptions& o,
                          scene::Scene* scene, const scene::Smoke& smoke, int frameCount);

// The flipbook job (without its output directory): frames, packing, camera, optics, tile and scattering.
reference::FlipbookBake bakeJob(const BakeOptions& o, const scene::Scene* scene, const BakeSource& source,
                                const scene::Smoke& smoke, BakeTile tile, int frameCount);

}  // namespace sixway::app
