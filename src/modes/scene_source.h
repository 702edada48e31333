#pragma once
// Where a scene's smoke comes from, for the tools that take any scene (render, eval, bake, dataset, the
// demo): its simulation, or its OpenVDB files played back (the scene's `vdb` section). The runtime does not
// read VDB files, so this is here, beside the modes, which link both it and the reference renderers.
#include <memory>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::modes {

// `frames` frames of the scene's smoke (frame i at (i + 1) · time.frame_dt). For a VDB scene, `scene.grid`
// becomes the playback lattice, so that what places cameras, billboards and depth ranges sees the smoke's
// box. Throws InputError naming `source` when a VDB scene has fewer frames than asked for.
std::unique_ptr<render::VolumeSequence> openSceneVolumes(const gpu::Context& context,
                                                         const gpu::PipelineCache& cache, scene::Scene& scene,
                                                         int frames, std::string_view source);

// What a report or sidecar records of where the smoke came from: the lattice, and the files when played back.
nlohmann::json describeSource(const render::VolumeSequence& volumes);

}  // namespace sixway::modes
