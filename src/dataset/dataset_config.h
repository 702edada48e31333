#pragma once
// The config of `sixway dataset` (docs/dataset-format.md): a base scene, how many sequences, the seeded
// per-sequence variations of its inlet, smoke and obstacles, the frames and cameras sampled, and the held-out
// rule. Read strictly like a scene (unknown keys and bad values are one-line io::InputErrors naming the file
// and the key). Everything random comes from the config's seed and the sequence index, so any sequence can be
// planned alone: that is what lets `--shard I/N` split the work.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/volume.h"
#include "scene/scene.h"

#include "reference/scattered_lightmaps.h"

namespace sixway::dataset {

// [min, max], min ≤ max; a single number in the file is [x, x].
struct Range {
  float min = 0, max = 0;
  float at(double u) const { return min + float(u) * (max - min); }
};

enum class ObstacleChoice { None, Cylinder, Sphere, Bunny, MovingSphere };
const char* obstacleChoiceName(ObstacleChoice choice);

struct DatasetObstacles {
  std::vector<ObstacleChoice> choices;  // sequence S gets choices[S mod size]
  Range radius;                         // m (a bunny: half its largest extent)
  Range height;                         // m, world y of the centre
  float offset = 0;                     // m, largest horizontal offset of the centre from the inlet's axis
  std::filesystem::path bunnyMesh;      // with "bunny": as written, relative to the config's folder
  Range movingSpeed;                    // with "moving_sphere": m/s
  float movingTravel = 0;               // with "moving_sphere": m, half the length of its path
};

struct DatasetVariations {  // each unset one keeps the base scene's value
  std::optional<Range> inletSpeed, inletRadius, inletDensity, inletTemperature;
  glm::vec3 inletOffset{0};  // m, largest offset of the inlet's centre per axis
  std::optional<Range> buoyancy, extinction, albedo;
  std::optional<Range> densityScale;  // × the (drawn or base) extinction, log-uniform; VDB scenes too
};

struct DatasetFrames {
  Range warmup;    // frames simulated before the first sample (integers), drawn per sequence
  int count = 1;   // samples per camera
  int stride = 1;  // frames between samples
};

struct DatasetCameras {
  std::vector<float> azimuthsDeg, elevationsDeg;
  float fovDeg = 40;
  std::optional<float> distance;  // m from the volume centre; default: the bounding sphere fills the view
};

// The lightmaps a shard stores as training targets ("targets": "single", "multiple" or "both"): `target`,
// the exact single-scattering baker's, and `target_ms`, multiply-scattered (reference::ScatteredLightmaps).
struct DatasetTargets {
  bool single = true, multiple = false;
  reference::MultipleScattering multipleScattering;  // "multiple_scattering": samples, orders, downsample
};

// A shard holds per sample the guide (3, or 4 with the fine alpha), targets (8 each) and motion (2) channels
// as F16 (dataset_sequence.h). It is built in host memory whole and read whole by the trainer, so its size is
// bounded when the config is read.
inline constexpr double kMaxShardBytes = 4.0 * (1 << 30);
int shardChannels(int guideChannels, const DatasetTargets& targets);

struct DatasetConfig {
  std::filesystem::path file;       // as given, for messages
  nlohmann::json json;              // the file's content, recorded in every shard
  std::filesystem::path baseScene;  // resolved against the config's folder
  nlohmann::json baseSceneJson;     // the base scene's file content
  int sequences = 1;
  uint32_t seed = 1;
  int attempts = 3;  // draws of a sequence's variations until its simulation runs (the watchdog passes)
  std::optional<glm::ivec3> gridSize;  // grid overrides
  std::optional<float> cellSize;
  std::optional<glm::vec3> origin;
  std::optional<int> smokeUpres;
  DatasetFrames frames;
  DatasetCameras cameras;
  int lightmapSize = 64;
  DatasetTargets targets;
  // "guide": {"alpha_step_voxels"}: > 0 adds the fine alpha as the guide's 4th channel (every sequence's
  // render.guide_alpha_step_voxels); default: the base scene's.
  float guideAlphaStepVoxels = 0;
  // "guide": {"emission"}: the fine march's direct emission as the guide's 5th channel (needs the fine
  // alpha).
  bool guideEmission = false;
  std::vector<int> heldoutSequences, heldoutCameras;
  DatasetVariations variations;
  std::optional<DatasetObstacles> obstacles;  // none: the base scene's obstacles
  // "vdb_scenes": scenes that play OpenVDB files back (resolved against the config's folder, with their
  // content). They are the sequences after the simulated ones: sequence `sequences + i` plays vdbScenes[i],
  // with the config's cameras, frames, lightmap size and smoke variations, and no motion field.
  std::vector<std::filesystem::path> vdbScenes;
  std::vector<nlohmann::json> vdbSceneJsons;

  int cameraCount() const { return int(cameras.azimuthsDeg.size() * cameras.elevationsDeg.size()); }
  int sequenceCount() const { return sequences + int(vdbScenes.size()); }
  // guide, alpha, depth[, alpha_fine[, emission]]
  int guideChannels() const { return guideEmission ? 5 : guideAlphaStepVoxels > 0 ? 4 : 3; }
};

// `file` names the config in errors and anchors its relative paths. Reads and checks the base scene too.
DatasetConfig parseDatasetConfig(const nlohmann::json& j, const std::filesystem::path& file);
DatasetConfig loadDatasetConfig(const std::filesystem::path& file);

// One sequence, planned from the config alone.
struct SequencePlan {
  int sequence = 0;
  int attempt = 0;           // 0, or the how-manieth redraw after the simulation failed
  nlohmann::json sceneJson;  // the effective scene (mesh paths relative to the config's folder)
  scene::Scene scene;        // parsed from sceneJson
  std::string obstacle;      // obstacleChoiceName, or "base" for the base scene's obstacles
  std::vector<int> frames;   // the sampled frame indices (frame i = the smoke after i + 1 frames)
};
// Attempt k > 0 draws the sequence's continuous variations anew (its obstacle choice stays). Throws
// io::InputError naming the config and the sequence when the varied scene is not a valid scene.
SequencePlan planSequence(const DatasetConfig& config, int sequence, int attempt = 0);
// The plan's scene with absolute mesh paths: a scene file that loads from any folder (e.g. for `sixway sim`).
nlohmann::json standaloneScene(const DatasetConfig& config, const SequencePlan& plan);

// Camera c = e · azimuths + a (elevation-major): looks at the volume box's centre from azimuth a (0: from +z,
// 90: from +x) and elevation e, up = +y.
struct DatasetCamera {
  int index = 0;
  float azimuthDeg = 0, elevationDeg = 0;
  render::Camera camera;
};
std::vector<DatasetCamera> datasetCameras(const DatasetConfig& config, const render::Box& volumeBox);

// "train", "heldout_sequence" or "heldout_camera" (docs/dataset-format.md, "Held-out rule").
std::string sampleSplit(const DatasetConfig& config, int sequence, int camera);

// `--shard I/N`: this worker does the sequences S with S mod N = I.
struct ShardSelection {
  int index = 0, count = 1;
  bool contains(int sequence) const { return sequence % count == index; }
};
// Throws io::InputError (source "--shard") unless `text` is "I/N" with 0 ≤ I < N.
ShardSelection parseShardSelection(const std::string& text);

// "shard_00042.safetensors"
std::string shardFileName(int sequence);

}  // namespace sixway::dataset
