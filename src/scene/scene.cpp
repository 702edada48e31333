#include "scene/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <nlohmann/json.hpp>

#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"
#include "scene/fluid_physics.h"

namespace sixway::scene {
namespace fs = std::filesystem;

// The file is read with io's JSON reader and its checks.
using io::atLeast;
using io::both;
using io::Choices;
using io::inOpenRange;
using io::InputError;
using io::inRange;
using io::JsonReader;
using io::lookupProblem;
using io::multipleOf;
using io::nonZero;
using io::parseJsonText;
using io::positive;
using io::readFileBytes;
using io::show;
using io::zeroOrInRange;

namespace {

// "" for a regular file; otherwise what the path is instead ("not found", "a directory", ...).
std::string notARegularFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::none) return lookupProblem(path, ec);  // a path beyond PATH_MAX, ...
  if (!fs::exists(status)) return "not found";
  if (fs::is_regular_file(status)) return "";
  if (fs::is_directory(status)) return "is a directory";
  return "is not a regular file (a FIFO, socket or device)";
}

// Beyond these a scene is a typo, not a simulation: refuse before anything is allocated.
constexpr std::int64_t kMaxCells = 512LL * 512 * 512;
constexpr int kMaxAxisCells = 2048;
constexpr std::int64_t kMaxSmokeCells = 1024LL * 1024 * 1024;
// The largest light, emission, ambient or background value: colour × intensity stays below 1e8, so that no
// product along a frame (phase function, emission ramp, exposure) overflows a float into inf/NaN pixels.
constexpr double kMaxRadiometric = 1e4;

const Choices<BoundaryType> kBoundaryTypes = {{"no_slip", BoundaryType::NoSlip},
                                              {"free_slip", BoundaryType::FreeSlip},
                                              {"outflow", BoundaryType::Outflow},
                                              {"periodic", BoundaryType::Periodic},
                                              {"inflow", BoundaryType::Inflow}};
const Choices<InflowProfile> kInflowProfiles = {{"uniform", InflowProfile::Uniform},
                                                {"parabolic", InflowProfile::Parabolic}};
const Choices<ObstacleBoundary> kObstacleBoundaries = {{"half_way", ObstacleBoundary::HalfWay},
                                                       {"interpolated", ObstacleBoundary::Interpolated}};
const Choices<PopulationStorage> kPopulationStorages = {{"fp32", PopulationStorage::Fp32},
                                                        {"fp16", PopulationStorage::Fp16}};
constexpr std::array<std::string_view, 6> kFaceNames = {"x-", "x+", "y-", "y+", "z-", "z+"};

enum class InletShape { Disk, Box };
const Choices<InletShape> kInletShapes = {{"disk", InletShape::Disk}, {"box", InletShape::Box}};

enum class ObstacleType { Sphere, Cylinder, Capsule, Box, Mesh };
const Choices<ObstacleType> kObstacleTypes = {{"sphere", ObstacleType::Sphere},
                                              {"cylinder", ObstacleType::Cylinder},
                                              {"capsule", ObstacleType::Capsule},
                                              {"box", ObstacleType::Box},
                                              {"mesh", ObstacleType::Mesh}};

enum class CameraPathType { Orbit, Dolly };
const Choices<CameraPathType> kCameraPaths = {{"orbit", CameraPathType::Orbit},
                                              {"dolly", CameraPathType::Dolly}};

enum class LightType { Directional, Point };
const Choices<LightType> kLightTypes = {{"directional", LightType::Directional}, {"point", LightType::Point}};

enum class LightPathType { Orbit };  // the only one so far; the key is there to leave room for more
const Choices<LightPathType> kLightPaths = {{"orbit", LightPathType::Orbit}};

const Choices<GuideLight> kGuideLights = {{"front", GuideLight::Front},   {"top", GuideLight::Top},
                                          {"bottom", GuideLight::Bottom}, {"left", GuideLight::Left},
                                          {"right", GuideLight::Right},   {"back", GuideLight::Back}};
const Choices<ToneMap> kToneMaps = {{"clamp", ToneMap::Clamp}, {"aces", ToneMap::Aces}};

constexpr std::string_view kPlaybackOnly = "the scene plays back vdb files: there is no simulation to set up";
// Files (times frames_per_file) a vdb sequence plays.
constexpr int kMaxVdbFrames = 100000;

const Choices<VdbUp> kVdbUps = {{"y", VdbUp::Y}, {"z", VdbUp::Z}};

glm::vec3 direction(JsonReader& r, std::string_view key, glm::vec3 fallback) {
  return glm::normalize(r.optional<glm::vec3>(key, fallback, nonZero()));
}

glm::vec3 direction(JsonReader& r, std::string_view key) {
  return glm::normalize(r.required<glm::vec3>(key, nonZero()));
}

std::string showCells(const glm::ivec3& size) {
  return show(size.x) + "×" + show(size.y) + "×" + show(size.z);
}

// The lattice's box, grid.size × grid.cell_size, within kMaxSceneMetres on every axis.
void requireBoxWithinScene(JsonReader& r, const Grid& g) {
  const glm::vec3 box = glm::vec3(g.size) * g.cellSize;  // inf beyond a float: refused all the same
  if (std::max({box.x, box.y, box.z}) > kMaxSceneMetres)
    r.fail("cell_size", showCells(g.size) + " cells of " + show(g.cellSize) + " m make a box of more than " +
                            show(kMaxSceneMetres) + " m along an axis; reduce grid.cell_size");
}

Grid parseGrid(JsonReader& r) {
  Grid g;
  g.size = r.required<glm::ivec3>("size", atLeast(1));
  g.cellSize = r.required<float>("cell_size", positive());
  g.origin = r.optional<glm::vec3>("origin", g.origin, inRange(-kMaxSceneMetres, kMaxSceneMetres));
  g.smokeUpres = r.optional<int>("smoke_upres", g.smokeUpres, inRange(1, 4));

  for (int axis = 0; axis < 3; ++axis)
    if (g.size[axis] > kMaxAxisCells)
      r.fail("size", std::string("axis ") + "xyz"[axis] + " has " + show(g.size[axis]) +
                         " cells, more than " + show(kMaxAxisCells) +
                         "; reduce grid.size (and raise grid.cell_size to keep the domain)");
  const std::int64_t cells = std::int64_t(g.size.x) * g.size.y * g.size.z;
  if (cells > kMaxCells)
    r.fail("size",
           showCells(g.size) + " = " + std::to_string(cells) +
               " cells, more than 512³; reduce grid.size (and raise grid.cell_size to keep the domain)");
  const std::int64_t smokeCells = cells * g.smokeUpres * g.smokeUpres * g.smokeUpres;
  if (smokeCells > kMaxSmokeCells)
    r.fail("smoke_upres", "the smoke grid would have " + std::to_string(smokeCells) +
                              " cells, more than 1024³; reduce grid.smoke_upres or grid.size");
  requireBoxWithinScene(r, g);
  return g;
}

TimeStepping parseTime(JsonReader& r, bool playback) {
  TimeStepping t;
  t.frameDt = r.optional<float>("frame_dt", t.frameDt, positive());
  if (playback) {
    r.forbid("steps_per_frame", kPlaybackOnly);
    return t;
  }
  t.stepsPerFrame = r.optional<int>("steps_per_frame", t.stepsPerFrame, inRange(1, kMaxStepsPerFrame));
  return t;
}

Buoyancy parseBuoyancy(JsonReader& r) {
  Buoyancy b;
  b.temperature = r.optional<float>("temperature", b.temperature, atLeast(0));
  b.density = r.optional<float>("density", b.density);
  return b;
}

Fluid parseFluid(JsonReader& r) {
  Fluid f;
  f.viscosity = r.maybe<float>("viscosity", positive());
  f.reynolds = r.maybe<float>("reynolds", positive());
  const std::optional<float> referenceLength = r.maybe<float>("reference_length", positive());
  f.smagorinsky = r.optional<float>("smagorinsky", f.smagorinsky, inRange(0, 0.5));
  f.maxLatticeVelocity = r.optional<float>("max_lattice_velocity", f.maxLatticeVelocity, inRange(0.01, 0.3));
  f.obstacleBoundary = r.choice("obstacle_boundary", kObstacleBoundaries, f.obstacleBoundary);
  f.populationStorage = r.choice("population_storage", kPopulationStorages, f.populationStorage);
  f.buoyancy = r.object("buoyancy", parseBuoyancy);
  f.gravity = r.optional<glm::vec3>("gravity", f.gravity, nonZero());
  f.bodyForce = r.optional<glm::vec3>("body_force", f.bodyForce);
  r.finish();  // a misspelt "viscosity" explains the error below better than the error itself

  if (f.viscosity && f.reynolds) r.failHere("give exactly one of viscosity and reynolds, not both");
  if (!f.viscosity && !f.reynolds) r.failHere("give exactly one of viscosity (m²/s) and reynolds");
  if (f.reynolds && !referenceLength) r.fail("reference_length", "required key missing (reynolds needs it)");
  if (f.viscosity && referenceLength) r.fail("reference_length", "not allowed (only used with reynolds)");
  f.referenceLength = referenceLength.value_or(0);
  return f;
}

Boundaries parseBoundaries(JsonReader& r) {
  Boundaries b;
  for (int face = 0; face < 6; ++face)
    b.faces[face] = r.choice(kFaceNames[face], kBoundaryTypes, b.faces[face]);
  for (int face = 0; face < 6; ++face) {
    const int opposite = face ^ 1;  // x- <-> x+, ...
    if (b.faces[face] == BoundaryType::Periodic && b.faces[opposite] != BoundaryType::Periodic)
      r.fail(kFaceNames[face], "periodic needs the opposite face periodic too (" +
                                   std::string(kFaceNames[opposite]) + " is not)");
  }
  const auto inflow = std::ranges::find(b.faces, BoundaryType::Inflow);
  if (inflow == b.faces.end()) {
    r.forbid("wind", "only used by inflow faces, and no face is inflow");
    r.forbid("inflow_profile", "only used by inflow faces, and no face is inflow");
  } else {
    const std::string_view face = kFaceNames[inflow - b.faces.begin()];
    if (!r.has("wind")) r.fail("wind", "required key missing (face " + std::string(face) + " is inflow)");
    b.wind = r.required<glm::vec3>("wind");
    b.inflowProfile = r.choice("inflow_profile", kInflowProfiles, b.inflowProfile);
  }
  return b;
}

Inlet parseInlet(JsonReader& r) {
  Inlet in;
  switch (r.choice("shape", kInletShapes)) {
    case InletShape::Disk: {
      InletDisk disk;
      disk.center = r.required<glm::vec3>("center");
      disk.radius = r.required<float>("radius", positive());
      disk.normal = direction(r, "normal");
      in.shape = disk;
      in.velocity = disk.normal * r.optional<float>("velocity", 0.0f, atLeast(0));
      break;
    }
    case InletShape::Box: {
      InletBox box;
      box.min = r.required<glm::vec3>("min");
      box.max = r.required<glm::vec3>("max");
      if (!glm::all(glm::lessThan(box.min, box.max)))
        r.fail("max", "must be greater than min on every axis (min " + show(box.min) + ", max " +
                          show(box.max) + ")");
      in.shape = box;
      in.velocity = r.optional<glm::vec3>("velocity", in.velocity);
      break;
    }
  }
  in.density = r.optional<float>("density", in.density, atLeast(0));
  in.temperature = r.optional<float>("temperature", in.temperature, atLeast(0));
  in.start = r.optional<float>("start", in.start, atLeast(0));
  in.stop = r.optional<float>("stop", in.stop);
  if (in.stop <= in.start)
    r.fail("stop", "must be after start (" + show(in.start) + "); got " + show(in.stop));
  in.noise = r.optional<float>("noise", in.noise, inRange(0, 1));
  return in;
}

Keyframe parseKeyframe(JsonReader& r) {
  Keyframe k;
  k.time = r.required<float>("time");
  k.position = r.required<glm::vec3>("position");
  return k;
}

Motion parseMotion(JsonReader& r) {
  Motion m;
  m.keyframes = r.requiredObjects("keyframes", parseKeyframe, 2);
  for (std::size_t i = 1; i < m.keyframes.size(); ++i)
    if (m.keyframes[i].time <= m.keyframes[i - 1].time)
      r.fail("keyframes[" + std::to_string(i) + "].time", "keyframe times must increase: got " +
                                                              show(m.keyframes[i].time) + " after " +
                                                              show(m.keyframes[i - 1].time));
  m.loop = r.optional<bool>("loop", m.loop);
  return m;
}

Obstacle parseObstacle(JsonReader& r, const fs::path& baseDir) {
  Obstacle o;
  o.motion = r.optionalObject("motion", parseMotion);
  // A moving obstacle's position comes from its keyframes alone.
  auto position = [&](std::string_view key, std::optional<glm::vec3> fallback) {
    if (o.motion) {
      r.forbid(key, "the motion keyframes give the position");
      return o.motion->keyframes.front().position;
    }
    return fallback ? r.optional<glm::vec3>(key, *fallback) : r.required<glm::vec3>(key);
  };

  switch (r.choice("type", kObstacleTypes)) {
    case ObstacleType::Sphere: {
      SphereObstacle sphere;
      sphere.center = position("center", std::nullopt);
      sphere.radius = r.required<float>("radius", positive());
      o.shape = sphere;
      break;
    }
    case ObstacleType::Cylinder: {
      CylinderObstacle cylinder;
      cylinder.center = position("center", std::nullopt);
      cylinder.radius = r.required<float>("radius", positive());
      cylinder.height = r.required<float>("height", positive());
      cylinder.axis = direction(r, "axis", cylinder.axis);
      o.shape = cylinder;
      break;
    }
    case ObstacleType::Capsule: {
      CapsuleObstacle capsule;
      capsule.center = position("center", std::nullopt);
      capsule.radius = r.required<float>("radius", positive());
      capsule.height = r.required<float>("height", positive());
      if (capsule.height < 2 * capsule.radius)
        r.fail("height", "a capsule's full height holds both caps: at least 2 · radius = " +
                             show(2 * capsule.radius) + " (got " + show(capsule.height) + ")");
      capsule.axis = direction(r, "axis", capsule.axis);
      o.shape = capsule;
      break;
    }
    case ObstacleType::Box: {
      BoxObstacle box;
      box.center = position("center", std::nullopt);
      box.size = r.required<glm::vec3>("size", positive());
      o.shape = box;
      break;
    }
    case ObstacleType::Mesh: {
      MeshObstacle mesh;
      mesh.file = fs::absolute(baseDir / r.required<std::string>("file")).lexically_normal();
      if (const std::string problem = notARegularFile(mesh.file); !problem.empty())
        r.fail("file", "mesh file " + problem + ": " + mesh.file.string());
      mesh.scale = r.optional<float>("scale", mesh.scale, positive());
      mesh.translate = position("translate", mesh.translate);
      mesh.rotateDeg = r.optional<glm::vec3>("rotate_deg", mesh.rotateDeg);
      o.shape = mesh;
      break;
    }
  }
  o.shadows = r.optional<bool>("shadows", o.shadows);
  return o;
}

EmissionKey parseEmissionKey(JsonReader& r) {
  EmissionKey k;
  k.temperature = r.required<float>("temperature");
  k.color = r.required<glm::vec3>("color", inRange(0, kMaxRadiometric));
  return k;
}

Emission parseEmission(JsonReader& r) {
  Emission e;
  e.intensity = r.optional<float>("intensity", e.intensity, inRange(0, kMaxRadiometric));
  if (e.intensity > 0 && !r.has("ramp")) r.fail("ramp", "required key missing (intensity > 0 needs it)");
  e.ramp = r.objects("ramp", parseEmissionKey, 2, kMaxRampKeys);
  for (std::size_t i = 1; i < e.ramp.size(); ++i)
    if (e.ramp[i].temperature <= e.ramp[i - 1].temperature)
      r.fail("ramp[" + std::to_string(i) + "].temperature", "ramp temperatures must increase: got " +
                                                                show(e.ramp[i].temperature) + " after " +
                                                                show(e.ramp[i - 1].temperature));
  return e;
}

Smoke parseSmoke(JsonReader& r, bool playback) {
  Smoke s;
  if (playback) r.forbid("dissipation", kPlaybackOnly);
  s.extinction = r.optional<float>("extinction", s.extinction, positive());
  s.albedo = r.optional<float>("albedo", s.albedo, inRange(0, 1));
  s.phaseG = r.optional<float>("phase_g", s.phaseG, inRange(-0.99, 0.99));
  s.dissipation = r.optional<float>("dissipation", s.dissipation, atLeast(0));
  if (playback) {
    r.forbid("sparse", kPlaybackOnly);
    r.forbid("sparse_threshold", kPlaybackOnly);
  }
  s.sparse = r.optional<bool>("sparse", s.sparse);
  s.sparseThreshold = r.optional<float>("sparse_threshold", s.sparseThreshold, atLeast(0));
  s.emission = r.object("emission", parseEmission);
  return s;
}

std::variant<CameraOrbit, CameraDolly> parseCameraPath(JsonReader& r) {
  if (r.choice("type", kCameraPaths) == CameraPathType::Orbit)
    return CameraOrbit{.degreesPerFrame = r.required<float>("degrees_per_frame")};
  CameraDolly dolly;
  dolly.endPosition = r.required<glm::vec3>("end_position");
  dolly.frames = r.required<int>("frames", atLeast(1));
  return dolly;
}

Camera parseCamera(JsonReader& r) {
  Camera c;
  // Beyond a million metres a float cannot resolve a smoke volume of metres, and |target - position|²
  // overflows (a camera at 1e20 m was reported as "up must not be parallel").
  c.position = r.required<glm::vec3>("position", inRange(-kMaxSceneMetres, kMaxSceneMetres));
  c.target = r.required<glm::vec3>("target", inRange(-kMaxSceneMetres, kMaxSceneMetres));
  if (glm::distance(c.position, c.target) < 1e-6f)
    r.fail("target", "must differ from camera.position (both are " + show(c.position) + ")");
  c.up = direction(r, "up", c.up);
  if (glm::length(glm::cross(glm::normalize(c.target - c.position), c.up)) < 1e-3f)
    r.fail("up", "must not be parallel to the view direction (target - position)");
  c.fovDeg = r.optional<float>("fov_deg", c.fovDeg, inRange(1, 170));
  c.path = r.optionalObject("path", parseCameraPath);
  if (c.path && std::holds_alternative<CameraDolly>(*c.path) &&
      glm::distance(std::get<CameraDolly>(*c.path).endPosition, c.target) < 1e-6f)
    r.fail("path.end_position", "must differ from camera.target");
  return c;
}

LightOrbit parseLightOrbit(JsonReader& r, bool directional) {
  r.choice("type", kLightPaths);
  LightOrbit o;
  if (directional)
    r.forbid("center", "a directional light has no position; its direction turns about axis");
  else
    o.center = r.required<glm::vec3>("center");
  o.axis = direction(r, "axis", o.axis);
  o.degreesPerFrame = r.required<float>("degrees_per_frame");
  return o;
}

Light parseLight(JsonReader& r) {
  Light l;
  switch (r.choice("type", kLightTypes)) {
    case LightType::Directional:
      l.source = DirectionalLight{.direction = direction(r, "direction")};
      break;
    case LightType::Point:
      l.source = PointLight{.position = r.required<glm::vec3>("position")};
      break;
  }
  l.color = r.optional<glm::vec3>("color", l.color, inRange(0, kMaxRadiometric));
  l.intensity = r.optional<float>("intensity", l.intensity, inRange(0, kMaxRadiometric));
  l.shadows = r.optional<bool>("shadows", l.shadows);
  const bool directional = std::holds_alternative<DirectionalLight>(l.source);
  l.path = r.optionalObject("path", [directional](JsonReader& p) { return parseLightOrbit(p, directional); });
  return l;
}

Ambient parseAmbient(JsonReader& r) {
  const std::optional<glm::vec3> color = r.maybe<glm::vec3>("color", inRange(0, kMaxRadiometric));
  const auto sh = r.maybe<std::vector<glm::vec3>>("sh", [](const std::vector<glm::vec3>& c) -> std::string {
    if (c.size() != 4)
      return "expected 4 coefficients L0, L1x, L1y, L1z (got " + std::to_string(c.size()) + ")";
    for (const glm::vec3& coefficient : c)
      if (glm::any(glm::greaterThan(glm::abs(coefficient), glm::vec3(float(kMaxRadiometric)))))
        return "every component must be in [" + show(-kMaxRadiometric) + ", " + show(kMaxRadiometric) +
               "] (got " + show(coefficient) + ")";
    return "";
  });
  // Unity's light probes hold the cosine-convolved environment over π: L0 as it is, L1 scaled by 2/3 (the
  // clamped-cosine lobe's band-1 factor, 2π/3, over π). "unity_probe" takes such coefficients as they are.
  const bool unityProbe =
      r.choice<bool>("sh_convention", {{"radiance", false}, {"unity_probe", true}}, false);
  r.finish();  // a misspelt key explains the errors below better
  if (color && sh) r.failHere("give exactly one of color and sh, not both");
  if (color && r.has("sh_convention")) r.fail("sh_convention", "goes with sh, not color");
  if (color) return AmbientColor{.color = *color};
  if (!sh) r.failHere("give exactly one of color and sh");
  AmbientSh out;
  std::ranges::copy(*sh, out.coefficients.begin());
  if (unityProbe)
    for (int i = 1; i < 4; ++i) out.coefficients[i] *= 1.5f;
  return out;
}

RenderSettings parseRender(JsonReader& r) {
  RenderSettings s;
  s.width = r.optional<int>("width", s.width, inRange(16, 8192));
  s.height = r.optional<int>("height", s.height, inRange(16, 8192));
  s.lightmapSize = r.optional<int>("lightmap_size", s.lightmapSize, both(inRange(16, 4096), multipleOf(16)));
  s.guideStepVoxels = r.optional<float>("guide_step_voxels", s.guideStepVoxels,
                                        inRange(kMinGuideStepVoxels, kMaxGuideStepVoxels));
  s.guideAlphaStepVoxels = r.optional<float>("guide_alpha_step_voxels", s.guideAlphaStepVoxels,
                                             zeroOrInRange(kMinGuideStepVoxels, kMaxGuideStepVoxels));
  if (const auto names = r.maybe<std::vector<std::string>>("guide_lights")) {
    if (names->empty()) r.fail("guide_lights", "needs at least one light");
    s.guideLights.clear();
    for (std::size_t i = 0; i < names->size(); ++i) {
      const std::string key = "guide_lights[" + std::to_string(i) + "]";
      const GuideLight light = r.pick(key, (*names)[i], kGuideLights);
      if (std::ranges::count(s.guideLights, light) > 0)
        r.fail(key, "\"" + (*names)[i] + "\" is listed twice");
      s.guideLights.push_back(light);
    }
  }
  s.background = r.optional<glm::vec3>("background", s.background, inRange(0, kMaxRadiometric));
  s.shellThreshold = r.optional<float>("shell_threshold", s.shellThreshold, inOpenRange(0, 1));
  s.seed = r.optional<std::uint32_t>("seed", s.seed);
  s.warmupFrames = r.optional<int>("warmup_frames", s.warmupFrames, inRange(0, 100000));
  s.toneMap = r.choice("tone_map", kToneMaps, s.toneMap);
  s.exposureStops = r.optional<float>("exposure", s.exposureStops, inRange(-20, 20));
  return s;
}

}  // namespace

namespace {

fs::path existingVdbFile(JsonReader& r, std::string_view key, const fs::path& baseDir,
                         const std::string& name) {
  const fs::path file = fs::absolute(baseDir / name).lexically_normal();
  if (const std::string problem = notARegularFile(file); !problem.empty())
    r.fail(key, "vdb file " + problem + ": " + file.string());
  return file;
}

// "smoke_%06d.vdb" with frame 12 → "smoke_000012.vdb": exactly one %d, optionally zero-padded to a width.
std::string expandPattern(JsonReader& r, const std::string& pattern, int frame) {
  const std::size_t at = pattern.find('%');
  std::size_t end = at == std::string::npos ? at : at + 1;
  bool zeros = false;
  if (end != std::string::npos && end < pattern.size() && pattern[end] == '0') {
    zeros = true;
    ++end;
  }
  int width = 0;
  while (end != std::string::npos && end < pattern.size() &&
         std::isdigit(static_cast<unsigned char>(pattern[end])))
    width = std::min(width * 10 + (pattern[end++] - '0'), 32);
  if (end == std::string::npos || end >= pattern.size() || pattern[end] != 'd' ||
      pattern.find('%', end) != std::string::npos)
    r.fail("pattern", "must hold exactly one %d (or %0Nd) for the frame number (got \"" + pattern + "\")");
  std::string number = std::to_string(frame);
  if (int(number.size()) < width) number.insert(0, std::size_t(width) - number.size(), zeros ? '0' : ' ');
  return pattern.substr(0, at) + number + pattern.substr(end + 1);
}

VdbSource parseVdb(JsonReader& r, const fs::path& baseDir) {
  VdbSource v;
  const bool listed = r.has("files"), patterned = r.has("pattern");
  if (listed == patterned)
    r.failHere("give either \"files\" (a list) or \"pattern\" with \"first\" and \"last\"");
  if (listed) {
    for (std::string_view key : {"first", "last"}) r.forbid(key, "only used with \"pattern\"");
    const auto names = r.required<std::vector<std::string>>("files");
    if (names.empty() || names.size() > std::size_t(kMaxVdbFrames))
      r.fail("files",
             "needs 1 to " + show(kMaxVdbFrames) + " files (got " + std::to_string(names.size()) + ")");
    for (const std::string& name : names) v.files.push_back(existingVdbFile(r, "files", baseDir, name));
  } else {
    const auto pattern = r.required<std::string>("pattern");
    const int first = r.required<int>("first", inRange(0, 1000000000));
    const int last = r.required<int>("last", inRange(first, first + kMaxVdbFrames - 1));
    for (int frame = first; frame <= last; ++frame)
      v.files.push_back(existingVdbFile(r, "pattern", baseDir, expandPattern(r, pattern, frame)));
  }
  v.densityGrid = r.optional<std::string>("density_grid", v.densityGrid);
  v.temperatureGrid = r.maybe<std::string>("temperature_grid");
  v.densityScale = r.optional<float>("density_scale", v.densityScale, positive());
  v.framesPerFile = r.optional<int>("frames_per_file", v.framesPerFile, inRange(1, 1000));
  v.voxels = r.isString("voxels") ? r.pick("voxels", r.required<std::string>("voxels"),
                                           Choices<int>{{"native", kNativeVoxels}})
                                  : r.optional<int>("voxels", v.voxels, inRange(8, kMaxVdbVoxels));
  v.scale = r.optional<float>("scale", v.scale, inRange(1e-6, kMaxSceneMetres));
  v.translate = r.optional<glm::vec3>("translate", v.translate, inRange(-kMaxSceneMetres, kMaxSceneMetres));
  v.up = r.choice("up", kVdbUps, v.up);
  const auto inScene = inRange(-kMaxSceneMetres, kMaxSceneMetres);
  const auto boxMin = r.maybe<glm::vec3>("box_min", inScene), boxMax = r.maybe<glm::vec3>("box_max", inScene);
  if (boxMin.has_value() != boxMax.has_value())
    r.fail(boxMin ? "box_max" : "box_min", "box_min and box_max go together");
  if (boxMin) {
    if (!glm::all(glm::lessThan(*boxMin, *boxMax))) r.fail("box_max", "must exceed box_min on every axis");
    if (v.voxels == kNativeVoxels)
      r.fail("voxels", "\"native\" plays the files' own cells: it takes no box_min and box_max");
    v.box = std::pair(*boxMin, *boxMax);
  }
  if (v.densityGrid.empty()) r.fail("density_grid", "must name a grid");
  if (v.temperatureGrid && v.temperatureGrid->empty()) r.fail("temperature_grid", "must name a grid");
  return v;
}

// Where an inlet can mark cells, in lattice coordinates (cell i's centre at i + 0.5): a disk's bounding box
// (its radius across the normal, half a cell along it), a box between its corners.
std::pair<glm::vec3, glm::vec3> inletLatticeBounds(const Inlet& inlet, const Grid& g) {
  const auto toLattice = [&g](glm::vec3 p) { return (p - g.origin) / g.cellSize; };
  if (const auto* disk = std::get_if<InletDisk>(&inlet.shape)) {
    const glm::vec3 n = disk->normal;
    const glm::vec3 across = disk->radius / g.cellSize * glm::sqrt(glm::max(1.0f - n * n, 0.0f));
    const glm::vec3 reach = across + 0.5f * glm::abs(n);
    return {toLattice(disk->center) - reach, toLattice(disk->center) + reach};
  }
  const auto& box = std::get<InletBox>(inlet.shape);
  return {toLattice(box.min), toLattice(box.max)};
}

// Whether a cell centre of the lattice lies in [lo, hi) on every axis.
bool holdsACellCentre(glm::vec3 lo, glm::vec3 hi, glm::ivec3 cells) {
  for (int axis = 0; axis < 3; ++axis) {
    const float first = std::max(0.0f, std::ceil(lo[axis] - 0.5f));  // the first cell centred at or after lo
    if (first > float(cells[axis] - 1) || first + 0.5f >= hi[axis]) return false;
  }
  return true;
}

// An inlet that marks no cell emits no smoke: refused, as is a disk wider than the grid could hold (its box
// of cells would overflow the simulation's integer bounds).
void requireInletsInGrid(const JsonReader& r, const Scene& s) {
  const Grid& g = s.grid;
  const glm::vec3 extent = glm::vec3(g.size) * g.cellSize;
  const float diagonal = glm::length(extent);
  for (std::size_t i = 0; i < s.inlets.size(); ++i) {
    const std::string key = "inlets[" + std::to_string(i) + "]";
    if (const auto* disk = std::get_if<InletDisk>(&s.inlets[i].shape); disk && disk->radius > diagonal)
      r.fail(key + ".radius", "must be at most the grid's diagonal, " + show(diagonal) + " m (got " +
                                  show(disk->radius) + ")");
    const auto [lo, hi] = inletLatticeBounds(s.inlets[i], g);
    if (!holdsACellCentre(lo, hi, g.size))
      r.fail(key, "covers no cell of the grid, which spans " + show(g.origin) + " to " +
                      show(g.origin + extent) + " m in cells of " + show(g.cellSize) +
                      " m: no smoke would enter; move the inlet into the grid");
  }
}

}  // namespace

Scene parseScene(const nlohmann::json& j, std::string_view sourceName, const fs::path& baseDir) {
  JsonReader r(j, "", sourceName);
  Scene s;
  // The name goes into file names (`sim --vdb-out`) and onto the terminal: no control characters (a terminal
  // escape would be printed raw) and no path separators.
  s.name = r.optional<std::string>("name", fs::path(sourceName).stem().string(), [](const std::string& name) {
    const bool bad = name.empty() || std::ranges::any_of(name, [](unsigned char c) {
                       return c < 0x20 || c == 0x7f || c == '/' || c == '\\';
                     });
    return bad ? std::string("must be a non-empty name without control characters or slashes")
               : std::string();
  });
  s.vdb = r.optionalObject("vdb", [&baseDir](JsonReader& v) { return parseVdb(v, baseDir); });
  const bool playback = s.vdb.has_value();
  if (playback) {
    // Obstacles would neither move the recorded smoke nor be moved by it: refused rather than half-done.
    for (std::string_view key : {"grid", "fluid", "boundaries", "inlets", "obstacles"})
      r.forbid(key, kPlaybackOnly);
  } else {
    s.grid = r.object("grid", parseGrid);
    s.fluid = r.object("fluid", parseFluid);
    s.boundaries = r.object("boundaries", parseBoundaries);
    s.inlets = r.objects("inlets", parseInlet, 0, kMaxSceneInlets);
    s.obstacles = r.objects(
        "obstacles", [&baseDir](JsonReader& o) { return parseObstacle(o, baseDir); }, 0, kMaxSceneObstacles);
  }
  s.time = r.object("time", [playback](JsonReader& t) { return parseTime(t, playback); });
  s.smoke = r.object("smoke", [playback](JsonReader& m) { return parseSmoke(m, playback); });
  s.camera = r.object("camera", parseCamera);
  s.lights = r.objects("lights", parseLight, 0, kMaxSceneLights);
  s.ambient = r.optionalObject("ambient", parseAmbient);
  s.render = r.object("render", parseRender);
  r.finish();
  if (playback) {
    if (s.smoke.emission.intensity > 0 && !s.vdb->temperatureGrid)
      r.fail("smoke.emission", "needs a temperature: name the grid with vdb.temperature_grid");
    return s;
  }

  // Checks that need several sections.
  requireInletsInGrid(r, s);
  if (s.fluid.reynolds && referenceSpeed(s) <= 0)
    r.fail("fluid.reynolds", "needs a reference speed, but no inlet has a velocity and no face is inflow");
  if (const double steps = stepsForLatticeVelocity(s); steps > kMaxStepsPerFrame)
    r.fail("time.frame_dt", "the fastest inflow (" + show(referenceSpeed(s)) +
                                " m/s) or buoyant plume (up to " + show(buoyantSpeedBound(s)) +
                                " m/s) would need " + show(steps) +
                                " LBM steps per frame; reduce time.frame_dt or the inflow speed, or raise "
                                "grid.cell_size or fluid.max_lattice_velocity");
  return s;
}

Scene loadScene(const fs::path& file) {
  const std::vector<uint8_t> bytes = readFileBytes(file);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const fs::path baseDir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  return parseSceneText(text, file.string(), baseDir);
}

Scene parseSceneText(std::string_view text, const std::string& name, const fs::path& baseDir) {
  return parseScene(parseJsonText(text, name), name, baseDir);
}

int sceneFrameCount(const Scene& scene) {
  if (!scene.vdb) return std::numeric_limits<int>::max();
  return int(scene.vdb->files.size()) * scene.vdb->framesPerFile;
}

void requireSimulated(const Scene& scene, std::string_view source) {
  if (scene.vdb)
    throw InputError(source,
                     "the scene plays back vdb files: there is nothing to simulate (render, eval, bake "
                     "and dataset play it back)");
}

}  // namespace sixway::scene
