#include "dataset/dataset_config.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <regex>
#include <set>

#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "io/obj.h"
#include "render/obstacle_meshes.h"
#include "scene/obstacle_placement.h"

namespace sixway::dataset {
namespace {

namespace fs = std::filesystem;

// Lists of numbers and of indices, for the JSON reader.
struct NumberList {
  std::vector<float> values;
};
struct IndexList {
  std::vector<int> values;
};

}  // namespace
}  // namespace sixway::dataset

namespace sixway::io {

template <>
struct JsonDecode<dataset::Range> {
  static constexpr const char* expected = "a number or an array [min, max]";
  static std::optional<dataset::Range> from(const nlohmann::json& v) {
    if (auto x = JsonDecode<float>::from(v)) return dataset::Range{*x, *x};
    if (!v.is_array() || v.size() != 2) return std::nullopt;
    auto lo = JsonDecode<float>::from(v[0]), hi = JsonDecode<float>::from(v[1]);
    if (!lo || !hi) return std::nullopt;
    return dataset::Range{*lo, *hi};
  }
};

template <>
struct JsonDecode<dataset::NumberList> {
  static constexpr const char* expected = "an array of numbers";
  static std::optional<dataset::NumberList> from(const nlohmann::json& v) {
    if (!v.is_array()) return std::nullopt;
    dataset::NumberList list;
    for (const nlohmann::json& e : v) {
      auto x = JsonDecode<float>::from(e);
      if (!x) return std::nullopt;
      list.values.push_back(*x);
    }
    return list;
  }
};

template <>
struct JsonDecode<dataset::IndexList> {
  static constexpr const char* expected = "an array of integers";
  static std::optional<dataset::IndexList> from(const nlohmann::json& v) {
    if (!v.is_array()) return std::nullopt;
    dataset::IndexList list;
    for (const nlohmann::json& e : v) {
      auto x = JsonDecode<int>::from(e);
      if (!x) return std::nullopt;
      list.values.push_back(*x);
    }
    return list;
  }
};

}  // namespace sixway::io

namespace sixway::dataset {
namespace {

std::string showRange(const Range& r) {
  return "[" + io::show(r.min) + ", " + io::show(r.max) + "]";
}

// A range within [lo, hi] (lo excluded when `openLow`), min ≤ max.
auto rangeWithin(double lo, double hi, bool openLow = false) {
  return [=](const Range& r) -> std::string {
    if (!(r.min <= r.max)) return "expected [min, max] with min <= max (got " + showRange(r) + ")";
    const bool lowOk = openLow ? r.min > lo : r.min >= lo;
    if (lowOk && r.max <= hi) return "";
    const std::string bound = hi == HUGE_VAL ? (openLow ? "> " : ">= ") + io::show(lo)
                                             : "in [" + io::show(lo) + ", " + io::show(hi) + "]";
    return "must be " + bound + " (got " + showRange(r) + ")";
  };
}
auto positiveRange() {
  return rangeWithin(0.0, HUGE_VAL, true);
}
auto nonNegativeRange() {
  return rangeWithin(0.0, HUGE_VAL);
}

auto numbersWithin(double lo, double hi) {
  return [=](const NumberList& list) -> std::string {
    if (list.values.empty()) return "needs at least one value";
    for (float v : list.values)
      if (!(v > lo && v < hi))
        return "every value must be in (" + io::show(lo) + ", " + io::show(hi) + ") (got " + io::show(v) +
               ")";
    return "";
  };
}

auto indicesBelow(int count, const char* what) {
  return [=](const IndexList& list) -> std::string {
    std::set<int> seen;
    for (int i : list.values) {
      if (i < 0 || i >= count)
        return "index " + std::to_string(i) + " is outside the " + std::to_string(count) + " " + what;
      if (!seen.insert(i).second) return "lists " + std::to_string(i) + " twice";
    }
    return "";
  };
}

const io::Choices<ObstacleChoice> kObstacleChoices = {{"none", ObstacleChoice::None},
                                                      {"cylinder", ObstacleChoice::Cylinder},
                                                      {"sphere", ObstacleChoice::Sphere},
                                                      {"bunny", ObstacleChoice::Bunny},
                                                      {"moving_sphere", ObstacleChoice::MovingSphere}};

fs::path resolve(const fs::path& dir, const fs::path& path) {
  return path.is_absolute() ? path : (dir / path).lexically_normal();
}

fs::path folderOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

DatasetObstacles parseObstacles(io::JsonReader& r, const fs::path& configDir) {
  DatasetObstacles o;
  const std::vector<std::string> names = r.required<std::vector<std::string>>("choices");
  if (names.empty()) r.fail("choices", "needs at least one choice");
  for (const std::string& name : names) o.choices.push_back(r.pick("choices", name, kObstacleChoices));
  o.radius = r.required<Range>("radius", positiveRange());
  o.height = r.required<Range>("height", rangeWithin(-HUGE_VAL, HUGE_VAL));
  o.offset = r.optional<float>("offset", 0.0f, io::atLeast(0));
  const auto uses = [&](ObstacleChoice c) { return std::ranges::count(o.choices, c) > 0; };
  if (uses(ObstacleChoice::Bunny)) {
    o.bunnyMesh = r.required<std::string>("bunny_mesh");
    const fs::path mesh = resolve(configDir, o.bunnyMesh);
    if (!fs::is_regular_file(mesh)) r.fail("bunny_mesh", "no such file '" + mesh.string() + "'");
  } else {
    r.forbid("bunny_mesh", "no choice is \"bunny\"");
  }
  if (uses(ObstacleChoice::MovingSphere)) {
    o.movingSpeed = r.required<Range>("moving_speed", positiveRange());
    o.movingTravel = r.required<float>("moving_travel", io::positive());
  } else {
    r.forbid("moving_speed", "no choice is \"moving_sphere\"");
    r.forbid("moving_travel", "no choice is \"moving_sphere\"");
  }
  return o;
}

DatasetVariations parseVariations(io::JsonReader& r) {
  DatasetVariations v;
  v.inletSpeed = r.maybe<Range>("inlet_speed", nonNegativeRange());
  v.inletRadius = r.maybe<Range>("inlet_radius", positiveRange());
  v.inletOffset = r.optional<glm::vec3>("inlet_offset", glm::vec3(0.0f), io::atLeast(0));
  v.inletDensity = r.maybe<Range>("inlet_density", nonNegativeRange());
  v.inletTemperature = r.maybe<Range>("inlet_temperature", nonNegativeRange());
  v.buoyancy = r.maybe<Range>("buoyancy", nonNegativeRange());
  v.extinction = r.maybe<Range>("extinction", positiveRange());
  v.albedo = r.maybe<Range>("albedo", rangeWithin(0.0, 1.0));
  v.densityScale = r.maybe<Range>("density_scale", positiveRange());
  return v;
}

bool variesInlet(const DatasetVariations& v) {
  return v.inletSpeed || v.inletRadius || v.inletDensity || v.inletTemperature ||
         v.inletOffset != glm::vec3(0.0f);
}

// The cell size of the config's sequences, in double as the files hold it (so the scene files stay tidy):
// the config's, else the base scene's scaled so that the domain keeps its extent along x.
double effectiveCellSize(const DatasetConfig& c, const scene::Grid& base) {
  if (c.cellSize) return c.json["grid"]["cell_size"].get<double>();
  const double baseCell = c.baseSceneJson["grid"]["cell_size"].get<double>();
  return c.gridSize ? baseCell * base.size.x / c.gridSize->x : baseCell;
}

// The lattice a config's sequences share: the base grid with the config's overrides. A domain of another
// extent keeps the base domain's floor and horizontal centre, unless the config gives the origin.
scene::Grid effectiveGrid(const DatasetConfig& c, const scene::Grid& base) {
  scene::Grid g = base;
  if (c.gridSize) g.size = *c.gridSize;
  g.cellSize = float(effectiveCellSize(c, base));
  if (c.smokeUpres) g.smokeUpres = *c.smokeUpres;
  const glm::vec3 grown = glm::vec3(g.size) * g.cellSize - glm::vec3(base.size) * base.cellSize;
  g.origin = c.origin ? *c.origin : base.origin - 0.5f * glm::vec3(grown.x, 0.0f, grown.z);
  return g;
}

// --- randomness: one independent uniform number per (seed, sequence, slot) ------------------------------

enum Slot : uint64_t {
  kSceneSeed,
  kWarmup,
  kInletSpeed,
  kInletRadius,
  kInletOffsetX,
  kInletOffsetY,
  kInletOffsetZ,
  kInletDensity,
  kInletTemperature,
  kBuoyancy,
  kExtinction,
  kAlbedo,
  kObstacleX,
  kObstacleZ,
  kObstacleHeight,
  kObstacleRadius,
  kObstacleAngle,
  kMovingSpeed,
  kDensityScale,  // appended: slots keep their numbers, so older configs plan as they did
};

uint64_t splitMix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A plan's draws: (seed, sequence, attempt).
struct Draws {
  uint32_t seed;
  int sequence, attempt;
};

uint64_t hashOf(const Draws& d, Slot slot) {
  return splitMix(splitMix(splitMix(d.seed) ^ uint64_t(d.sequence)) ^ uint64_t(slot) ^
                  (uint64_t(d.attempt) << 40));
}

// In [0, 1).
double uniform(const Draws& d, Slot slot) {
  return double(hashOf(d, slot) >> 11) * 0x1.0p-53;
}

// Drawn values are written into the scene rounded to 10⁻⁴, so that the scene file reads well; the scene that
// runs is the one parsed back from it.
double tidy(double v) {
  return std::round(v * 1e4) / 1e4;
}
nlohmann::json tidy(glm::vec3 v) {
  return {tidy(v.x), tidy(v.y), tidy(v.z)};
}

// A mesh path of the base scene, relative to the base scene's folder, made relative to the config's folder.
std::string rebase(const std::string& file, const fs::path& baseDir, const fs::path& configDir) {
  if (fs::path(file).is_absolute()) return file;
  const fs::path target = fs::absolute(baseDir / file).lexically_normal();
  const fs::path relative = target.lexically_relative(fs::absolute(configDir).lexically_normal());
  return relative.empty() ? target.string() : relative.generic_string();
}

nlohmann::json obstacleJson(const DatasetConfig& c, const Draws& s, ObstacleChoice choice,
                            glm::vec3 inletCentre, const scene::Grid& grid) {
  const DatasetObstacles& o = *c.obstacles;
  const glm::vec3 centre(inletCentre.x + float(2 * uniform(s, kObstacleX) - 1) * o.offset,
                         o.height.at(uniform(s, kObstacleHeight)),
                         inletCentre.z + float(2 * uniform(s, kObstacleZ) - 1) * o.offset);
  const float radius = o.radius.at(uniform(s, kObstacleRadius));
  const double angle = uniform(s, kObstacleAngle) * std::numbers::pi;  // about y, from +x
  const glm::vec3 across(float(std::cos(angle)), 0.0f, float(std::sin(angle)));
  switch (choice) {
    case ObstacleChoice::None:
      break;
    case ObstacleChoice::Cylinder: {
      // A horizontal rod across the plume, half as long as the domain's narrower horizontal side.
      const glm::vec3 extent = glm::vec3(grid.size) * grid.cellSize;
      return {{"type", "cylinder"},
              {"center", tidy(centre)},
              {"radius", tidy(radius)},
              {"height", tidy(0.5 * std::min(extent.x, extent.z))},
              {"axis", tidy(across)}};
    }
    case ObstacleChoice::Sphere:
      return {{"type", "sphere"}, {"center", tidy(centre)}, {"radius", tidy(radius)}};
    case ObstacleChoice::Bunny: {
      // Scaled so that half its largest extent is `radius`, turned about y, its bounding box centred.
      const io::Mesh mesh = io::readObj(resolve(folderOf(c.file), o.bunnyMesh));
      const glm::vec3 size = mesh.boundsMax - mesh.boundsMin;
      const double scale = tidy(2.0f * radius / std::max({size.x, size.y, size.z}));
      const double turn = tidy(glm::degrees(2.0 * angle));
      scene::MeshObstacle placed;
      placed.scale = float(scale);
      placed.rotateDeg = glm::vec3(0.0f, float(turn), 0.0f);
      const glm::vec3 middle = 0.5f * (mesh.boundsMin + mesh.boundsMax);
      const glm::vec3 translate = centre - scene::meshRotation(placed) * (placed.scale * middle);
      return {{"type", "mesh"},
              {"file", o.bunnyMesh.generic_string()},
              {"scale", scale},
              {"translate", tidy(translate)},
              {"rotate_deg", {0.0, turn, 0.0}}};
    }
    case ObstacleChoice::MovingSphere: {
      // Back and forth through the plume's axis along `across`, starting at one end.
      const float speed = o.movingSpeed.at(uniform(s, kMovingSpeed));
      const double leg = tidy(2.0 * o.movingTravel / speed);
      const nlohmann::json a = tidy(centre - o.movingTravel * across),
                           b = tidy(centre + o.movingTravel * across);
      return {{"type", "sphere"},
              {"radius", tidy(radius)},
              {"motion",
               {{"keyframes",
                 {{{"time", 0.0}, {"position", a}},
                  {{"time", leg}, {"position", b}},
                  {{"time", 2 * leg}, {"position", a}}}},
                {"loop", true}}}};
    }
  }
  return nullptr;
}

// "targets" and, for multiple scattering, "multiple_scattering" {samples, orders, downsample}.
DatasetTargets parseTargets(io::JsonReader& r) {
  DatasetTargets t;
  const std::string which = r.optional<std::string>("targets", "single", [](const std::string& s) {
    return s == "single" || s == "multiple" || s == "both"
               ? ""
               : "must be \"single\", \"multiple\" or \"both\" (got \"" + s + "\")";
  });
  t.single = which != "multiple";
  t.multiple = which != "single";
  if (!t.multiple) {
    r.forbid("multiple_scattering", "targets is \"single\"");
    return t;
  }
  t.multipleScattering = r.object("multiple_scattering", [](io::JsonReader& m) {
    reference::MultipleScattering ms;
    ms.samples = uint32_t(m.optional<int>("samples", int(ms.samples), io::inRange(1, 1 << 20)));
    ms.maxOrders = m.optional<int>("orders", ms.maxOrders, io::inRange(2, 100000));
    ms.downsample = m.optional<int>("downsample", ms.downsample, [](int d) {
      return d == 1 || d == 2 || d == 4 || d == 8 ? ""
                                                  : "must be 1, 2, 4 or 8 (got " + std::to_string(d) + ")";
    });
    return ms;
  });
  return t;
}

}  // namespace

const char* obstacleChoiceName(ObstacleChoice choice) {
  for (const auto& [name, value] : kObstacleChoices)
    if (value == choice) return name.data();
  return "?";
}

int shardChannels(int guideChannels, const DatasetTargets& targets) {
  return guideChannels + 8 * (int(targets.single) + int(targets.multiple)) + 2;
}

DatasetConfig parseDatasetConfig(const nlohmann::json& j, const fs::path& file) {
  DatasetConfig c;
  c.file = file;
  c.json = j;
  const fs::path dir = folderOf(file);
  io::JsonReader r(j, "", file.string());
  r.optional<std::string>("description", "");

  c.baseScene = resolve(dir, r.required<std::string>("base_scene"));
  if (!fs::is_regular_file(c.baseScene)) r.fail("base_scene", "no such file '" + c.baseScene.string() + "'");
  const std::vector<uint8_t> bytes = io::readFileBytes(c.baseScene);
  c.baseSceneJson = io::parseJsonText(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), c.baseScene.string());
  const scene::Scene base = scene::parseScene(c.baseSceneJson, c.baseScene.string(), folderOf(c.baseScene));

  c.sequences = r.required<int>("sequences", io::inRange(1, 100000));
  c.seed = r.optional<uint32_t>("seed", 1u);
  c.attempts = r.optional<int>("attempts", 3, io::inRange(1, 100));
  r.object("grid", [&](io::JsonReader& g) {
    c.gridSize = g.maybe<glm::ivec3>("size", io::inRange(1, 2048));
    c.cellSize = g.maybe<float>("cell_size", io::positive());
    c.origin = g.maybe<glm::vec3>("origin");
    c.smokeUpres = g.maybe<int>("smoke_upres", io::inRange(1, 4));
    if (c.cellSize && !c.gridSize) g.fail("cell_size", "goes with size");
    return 0;
  });
  r.object("frames", [&](io::JsonReader& f) {
    c.frames.warmup = f.optional<Range>("warmup", Range{}, [](const Range& w) {
      const std::string problem = nonNegativeRange()(w);
      if (!problem.empty()) return problem;
      return w.min == std::floor(w.min) && w.max == std::floor(w.max)
                 ? ""
                 : "must be whole frames (got " + showRange(w) + ")";
    });
    c.frames.count = f.required<int>("count", io::inRange(1, 100000));
    c.frames.stride = f.optional<int>("stride", 1, io::inRange(1, 100000));
    return 0;
  });
  r.object("cameras", [&](io::JsonReader& cam) {
    c.cameras.azimuthsDeg = cam.required<NumberList>("azimuths_deg", numbersWithin(-360.0, 360.0)).values;
    c.cameras.elevationsDeg =
        cam.optional<NumberList>("elevations_deg", NumberList{{0.0f}}, numbersWithin(-90.0, 90.0)).values;
    c.cameras.fovDeg = cam.optional<float>("fov_deg", base.camera.fovDeg, io::inRange(1, 170));
    c.cameras.distance = cam.maybe<float>("distance", io::positive());
    return 0;
  });
  c.lightmapSize = r.optional<int>("lightmap_size", base.render.lightmapSize,
                                   io::both(io::inRange(16, 4096), io::multipleOf(16)));
  c.targets = parseTargets(r);
  r.object("guide", [&](io::JsonReader& g) {
    c.guideAlphaStepVoxels =
        g.optional<float>("alpha_step_voxels", base.render.guideAlphaStepVoxels,
                          io::zeroOrInRange(scene::kMinGuideStepVoxels, scene::kMaxGuideStepVoxels));
    c.guideEmission = g.optional<bool>("emission", false);
    if (c.guideEmission && c.guideAlphaStepVoxels <= 0)
      g.fail("emission", "comes from the fine march: needs alpha_step_voxels > 0");
    return 0;
  });
  const double shardBytes = double(c.frames.count) * c.cameraCount() *
                            shardChannels(c.guideChannels(), c.targets) * 2.0 * c.lightmapSize *
                            c.lightmapSize;
  if (shardBytes > kMaxShardBytes)
    r.fail("frames.count", std::to_string(c.frames.count) + " frames x " + std::to_string(c.cameraCount()) +
                               " cameras of " + std::to_string(c.lightmapSize) +
                               "² lightmaps make shards of " +
                               io::show(std::round(shardBytes / (1 << 30) * 10) / 10) +
                               " GiB, more than 4 GiB; reduce frames.count, the cameras or lightmap_size "
                               "(more sequences hold more samples)");
  for (const std::string& name : r.optional<std::vector<std::string>>("vdb_scenes", {})) {
    const fs::path scene = resolve(dir, name);
    if (!fs::is_regular_file(scene)) r.fail("vdb_scenes", "no such file '" + scene.string() + "'");
    const std::vector<uint8_t> text = io::readFileBytes(scene);
    nlohmann::json json = io::parseJsonText(
        std::string_view(reinterpret_cast<const char*>(text.data()), text.size()), scene.string());
    const scene::Scene parsed = scene::parseScene(json, scene.string(), folderOf(scene));
    if (!parsed.vdb) r.fail("vdb_scenes", "'" + scene.string() + "' has no vdb section: it simulates");
    const int needed = int(c.frames.warmup.max) + (c.frames.count - 1) * c.frames.stride + 1;
    if (needed > scene::sceneFrameCount(parsed))
      r.fail("vdb_scenes", "'" + scene.string() + "' has " + std::to_string(scene::sceneFrameCount(parsed)) +
                               " frames; frames.warmup, count and stride need " + std::to_string(needed));
    c.vdbScenes.push_back(scene);
    c.vdbSceneJsons.push_back(std::move(json));
  }
  r.object("heldout", [&](io::JsonReader& h) {
    c.heldoutSequences =
        h.optional<IndexList>("sequences", {}, indicesBelow(c.sequenceCount(), "sequences")).values;
    c.heldoutCameras = h.optional<IndexList>("cameras", {}, indicesBelow(c.cameraCount(), "cameras")).values;
    return 0;
  });
  c.variations = r.object("variations", parseVariations);
  c.obstacles = r.optionalObject("obstacles", [&](io::JsonReader& o) { return parseObstacles(o, dir); });
  r.finish();

  if (variesInlet(c.variations) && base.inlets.empty())
    r.fail("variations",
           "the inlet variations need an inlet in the base scene (" + c.baseScene.string() + ")");
  if (c.variations.inletRadius && !std::holds_alternative<scene::InletDisk>(base.inlets[0].shape))
    r.fail("variations.inlet_radius",
           "needs a disk as the base scene's first inlet (" + c.baseScene.string() + " has a box)");
  if (c.variations.inletSpeed && std::holds_alternative<scene::InletBox>(base.inlets[0].shape) &&
      glm::length(base.inlets[0].velocity) == 0.0f)
    r.fail("variations.inlet_speed",
           "the base scene's box inlet has no velocity to scale (" + c.baseScene.string() + ")");
  if (c.cameras.distance) {
    const scene::Grid grid = effectiveGrid(c, base.grid);
    const float radius = 0.5f * glm::length(glm::vec3(grid.size) * grid.cellSize);
    if (*c.cameras.distance <= radius)
      r.fail("cameras.distance", "must be more than the volume's bounding radius " + io::show(radius) +
                                     " m (got " + io::show(*c.cameras.distance) + ")");
  }
  return c;
}

DatasetConfig loadDatasetConfig(const fs::path& file) {
  const std::vector<uint8_t> bytes = io::readFileBytes(file);
  return parseDatasetConfig(
      io::parseJsonText(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                        file.string()),
      file);
}

namespace {

glm::vec3 inletCentreOf(const scene::Inlet& inlet) {
  if (const auto* disk = std::get_if<scene::InletDisk>(&inlet.shape)) return disk->center;
  const auto& box = std::get<scene::InletBox>(inlet.shape);
  return 0.5f * (box.min + box.max);
}

// Draws the first inlet's variations into its scene JSON and returns its (moved) centre. A disk's speed is
// along its normal; a box keeps its velocity's direction at the drawn speed, and its offset moves both
// corners.
glm::vec3 varyInlet(nlohmann::json& inlet, const scene::Inlet& base, const DatasetVariations& v,
                    const Draws& s) {
  const bool disk = std::holds_alternative<scene::InletDisk>(base.shape);
  if (v.inletSpeed) {
    const double speed = v.inletSpeed->at(uniform(s, kInletSpeed));
    inlet["velocity"] =
        disk ? nlohmann::json(tidy(speed)) : tidy(glm::normalize(base.velocity) * float(speed));
  }
  if (v.inletRadius) inlet["radius"] = tidy(v.inletRadius->at(uniform(s, kInletRadius)));
  if (v.inletDensity) inlet["density"] = tidy(v.inletDensity->at(uniform(s, kInletDensity)));
  if (v.inletTemperature) inlet["temperature"] = tidy(v.inletTemperature->at(uniform(s, kInletTemperature)));
  const glm::vec3 u(uniform(s, kInletOffsetX), uniform(s, kInletOffsetY), uniform(s, kInletOffsetZ));
  const glm::vec3 offset = (2.0f * u - 1.0f) * v.inletOffset;
  if (disk) {
    inlet["center"] = tidy(inletCentreOf(base) + offset);
  } else {
    const auto& box = std::get<scene::InletBox>(base.shape);
    inlet["min"] = tidy(box.min + offset);
    inlet["max"] = tidy(box.max + offset);
  }
  return inletCentreOf(base) + offset;
}

void varySmoke(nlohmann::json& scene, const DatasetVariations& v, const Draws& s) {
  nlohmann::json& smoke = scene["smoke"];
  if (v.extinction) smoke["extinction"] = tidy(v.extinction->at(uniform(s, kExtinction)));
  if (v.albedo) smoke["albedo"] = tidy(v.albedo->at(uniform(s, kAlbedo)));
  if (v.densityScale) {  // log-uniform: x0.5 and x2 are equally likely around x1
    const double scale = v.densityScale->min * std::pow(double(v.densityScale->max) / v.densityScale->min,
                                                        uniform(s, kDensityScale));
    smoke["extinction"] = tidy(smoke.value("extinction", double(scene::Smoke{}.extinction)) * scale);
  }
}

// The first sampled frame is drawn from frames.warmup, the rest follow every stride frames.
std::vector<int> sampledFrames(const DatasetConfig& c, const Draws& s) {
  const int warmup = std::min(
      int(c.frames.warmup.max),
      int(c.frames.warmup.min) + int(uniform(s, kWarmup) * (c.frames.warmup.max - c.frames.warmup.min + 1)));
  std::vector<int> frames;
  for (int k = 0; k < c.frames.count; ++k) frames.push_back(warmup + k * c.frames.stride);
  return frames;
}

std::string sequenceSuffix(int sequence) {
  char suffix[16];
  std::snprintf(suffix, sizeof(suffix), "_%05d", sequence);
  return suffix;
}

// Sequence `sequence` ≥ c.sequences: a VDB scene played back, its files listed with absolute paths so that
// the plan's scene loads from any folder. Only the smoke's variations apply: there is no inlet or flow.
// The config's guide into a sequence's scene (left out when off and the base scene has no such key, so that
// the scenes of configs without it stay what they were).
void setGuide(nlohmann::json& scene, const DatasetConfig& c) {
  nlohmann::json& render = scene["render"];
  if (c.guideAlphaStepVoxels > 0 || render.contains("guide_alpha_step_voxels"))
    render["guide_alpha_step_voxels"] = c.guideAlphaStepVoxels;
}

SequencePlan planVdbSequence(const DatasetConfig& c, int sequence, int attempt) {
  const Draws s{c.seed, sequence, attempt};
  const std::size_t i = std::size_t(sequence - c.sequences);
  const scene::Scene played =
      scene::parseScene(c.vdbSceneJsons[i], c.vdbScenes[i].string(), folderOf(c.vdbScenes[i]));
  SequencePlan plan;
  plan.sequence = sequence;
  plan.attempt = attempt;
  plan.obstacle = "none";
  nlohmann::json& j = plan.sceneJson;
  j = c.vdbSceneJsons[i];
  j["name"] = played.name + sequenceSuffix(sequence);
  for (const char* key : {"pattern", "first", "last"}) j["vdb"].erase(key);
  j["vdb"]["files"] = nlohmann::json::array();
  for (const fs::path& file : played.vdb->files) j["vdb"]["files"].push_back(file.string());
  j["render"]["lightmap_size"] = c.lightmapSize;
  j["render"]["seed"] = uint32_t(hashOf(s, kSceneSeed));
  setGuide(j, c);
  varySmoke(j, c.variations, s);
  plan.frames = sampledFrames(c, s);
  plan.scene = scene::parseScene(j, c.file.string() + " (sequence " + std::to_string(sequence) + ")",
                                 folderOf(c.file));
  return plan;
}

}  // namespace

SequencePlan planSequence(const DatasetConfig& c, int sequence, int attempt) {
  if (sequence >= c.sequences) return planVdbSequence(c, sequence, attempt);
  const Draws s{c.seed, sequence, attempt};
  const fs::path configDir = folderOf(c.file);
  const scene::Scene base = scene::parseScene(c.baseSceneJson, c.baseScene.string(), folderOf(c.baseScene));
  SequencePlan plan;
  plan.sequence = sequence;
  plan.attempt = attempt;
  nlohmann::json& j = plan.sceneJson;
  j = c.baseSceneJson;
  j["name"] = base.name + sequenceSuffix(sequence);

  const scene::Grid grid = effectiveGrid(c, base.grid);
  j["grid"]["size"] = {grid.size.x, grid.size.y, grid.size.z};
  j["grid"]["cell_size"] = effectiveCellSize(c, base.grid);
  j["grid"]["smoke_upres"] = grid.smokeUpres;
  j["grid"]["origin"] = tidy(grid.origin);
  j["render"]["lightmap_size"] = c.lightmapSize;
  j["render"]["seed"] = uint32_t(hashOf(s, kSceneSeed));
  setGuide(j, c);

  const DatasetVariations& v = c.variations;
  glm::vec3 inletCentre = render::domainBox(grid).centre();
  if (!base.inlets.empty()) inletCentre = inletCentreOf(base.inlets[0]);
  if (variesInlet(v)) inletCentre = varyInlet(j["inlets"][0], base.inlets[0], v, s);
  if (v.buoyancy) j["fluid"]["buoyancy"]["temperature"] = tidy(v.buoyancy->at(uniform(s, kBuoyancy)));
  varySmoke(j, v, s);

  if (c.obstacles) {
    const ObstacleChoice choice = c.obstacles->choices[size_t(sequence) % c.obstacles->choices.size()];
    plan.obstacle = obstacleChoiceName(choice);
    j["obstacles"] = nlohmann::json::array();
    if (choice != ObstacleChoice::None)
      j["obstacles"].push_back(obstacleJson(c, s, choice, inletCentre, grid));
  } else {
    plan.obstacle = "base";
    if (j.contains("obstacles"))
      for (nlohmann::json& o : j["obstacles"])
        if (o.contains("file") && o["file"].is_string())
          o["file"] = rebase(o["file"].get<std::string>(), folderOf(c.baseScene), configDir);
  }

  plan.frames = sampledFrames(c, s);

  plan.scene =
      scene::parseScene(j, c.file.string() + " (sequence " + std::to_string(sequence) + ")", configDir);
  return plan;
}

nlohmann::json standaloneScene(const DatasetConfig& c, const SequencePlan& plan) {
  nlohmann::json j = plan.sceneJson;
  if (j.contains("obstacles"))
    for (nlohmann::json& o : j["obstacles"])
      if (o.contains("file") && o["file"].is_string())
        o["file"] =
            fs::absolute(resolve(folderOf(c.file), o["file"].get<std::string>())).lexically_normal().string();
  return j;
}

std::vector<DatasetCamera> datasetCameras(const DatasetConfig& c, const render::Box& box) {
  const glm::vec3 centre = box.centre();
  const float radius = 0.5f * glm::length(box.size());
  const float distance =
      c.cameras.distance ? *c.cameras.distance : radius / std::sin(glm::radians(0.5f * c.cameras.fovDeg));
  std::vector<DatasetCamera> cameras;
  for (float elevation : c.cameras.elevationsDeg)
    for (float azimuth : c.cameras.azimuthsDeg) {
      const float a = glm::radians(azimuth), e = glm::radians(elevation);
      const glm::vec3 direction(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
      cameras.push_back({int(cameras.size()), azimuth, elevation,
                         render::Camera::lookAt(centre + distance * direction, centre, glm::vec3(0, 1, 0),
                                                c.cameras.fovDeg)});
    }
  return cameras;
}

std::string sampleSplit(const DatasetConfig& c, int sequence, int camera) {
  if (std::ranges::count(c.heldoutSequences, sequence) > 0) return "heldout_sequence";
  if (std::ranges::count(c.heldoutCameras, camera) > 0) return "heldout_camera";
  return "train";
}

ShardSelection parseShardSelection(const std::string& text) {
  std::smatch m;
  if (std::regex_match(text, m, std::regex(R"((\d{1,9})/(\d{1,9}))"))) {
    const ShardSelection s{std::stoi(m[1]), std::stoi(m[2])};
    if (s.count >= 1 && s.index < s.count) return s;
  }
  throw io::InputError("--shard", "expected I/N with 0 <= I < N (got \"" + text + "\")");
}

std::string shardFileName(int sequence) {
  char name[32];
  std::snprintf(name, sizeof(name), "shard_%05d.safetensors", sequence);
  return name;
}

}  // namespace sixway::dataset
