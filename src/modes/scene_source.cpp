#include "modes/scene_source.h"

#include <nlohmann/json.hpp>

#include "io/error.h"
#include "reference/vdb_sequence.h"
#include "runtime/scene_volumes.h"

namespace sixway::modes {

std::unique_ptr<render::VolumeSequence> openSceneVolumes(const gpu::Context& context,
                                                         const gpu::PipelineCache& cache, scene::Scene& scene,
                                                         int frames, std::string_view source) {
  if (!scene.vdb) return std::make_unique<runtime::SimulatedVolumes>(context, cache, scene, frames);
  const int available = scene::sceneFrameCount(scene);
  if (frames > available)
    throw io::InputError(source, std::to_string(frames) + " frames asked for, but the vdb sequence has " +
                                     std::to_string(available) + " (" +
                                     std::to_string(scene.vdb->files.size()) + " files × frames_per_file " +
                                     std::to_string(scene.vdb->framesPerFile) + ")");
  auto volumes = std::make_unique<reference::VdbSequence>(context, *scene.vdb);
  const render::VolumeGrid& lattice = volumes->lattice();
  scene.grid = {lattice.size, lattice.cellSize, lattice.origin, 1};
  return volumes;
}

nlohmann::json describeSource(const render::VolumeSequence& volumes) {
  const render::Box box = volumes.bounds();
  nlohmann::json j = {
      {"bounds", {{"min", {box.min.x, box.min.y, box.min.z}}, {"max", {box.max.x, box.max.y, box.max.z}}}}};
  if (const auto* vdb = dynamic_cast<const reference::VdbSequence*>(&volumes)) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& file : vdb->source().files) files.push_back(file.string());
    const render::VolumeGrid& lattice = vdb->lattice();
    j["vdb"] = files;
    j["lattice"] = {{"cells", {lattice.size.x, lattice.size.y, lattice.size.z}},
                    {"origin", {lattice.origin.x, lattice.origin.y, lattice.origin.z}},
                    {"cell_size", lattice.cellSize}};
    j["notes"] = vdb->notes();
  }
  return j;
}

}  // namespace sixway::modes
