#pragma once
// A scene file (docs/scene-format.md), read into typed settings and validated as a whole: what
// loadScene returns can be used without further checks. World units: metres, seconds, y up.
// Directions (normals, axes, light directions, camera up) are normalised when read.
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

namespace sixway::io {
struct Mesh;
}  // namespace sixway::io

namespace sixway::scene {

// The most of each list a scene may hold: the fixed-size arrays of the shaders and parameter blocks that
// take them (checked against those at compile time in tests/app/test_scene_limits.cpp).
inline constexpr std::size_t kMaxSceneInlets = 8;      // sim::kMaxInlets
inline constexpr std::size_t kMaxSceneObstacles = 16;  // sim::kMaxObstacles
inline constexpr std::size_t kMaxSceneLights = 8;      // shaders/render/path_trace.comp, obstacle_params.glsl
inline constexpr std::size_t kMaxRampKeys = 16;        // shaders/common/emission.glsl
inline constexpr int kMaxStepsPerFrame = 10000;        // LBM steps in one frame

// The farthest a scene's positions reach from the origin and the longest side of a smoke box, in metres:
// beyond them a box's diagonal overflows a float (the renderers' light grids then have no size) long before
// any smoke scene needs them.
inline constexpr double kMaxSceneMetres = 1e6;
// The guide's ray-march steps (render.guide_step_voxels, render.guide_alpha_step_voxels, a network's
// guide_alpha_step_voxels), in smoke cells: finer, a ray has too many steps to march (and its float position
// stops advancing); coarser, the steps jump over the smoke.
inline constexpr double kMinGuideStepVoxels = 0.05;
inline constexpr double kMaxGuideStepVoxels = 16;

// The LBM lattice. Cell (i,j,k) has its centre at origin + (i+0.5, j+0.5, k+0.5)·cellSize.
struct Grid {
  glm::ivec3 size{0};
  float cellSize = 0;  // m
  glm::vec3 origin{0};
  int smokeUpres = 1;  // the smoke grid is this many times finer on each axis
};

struct TimeStepping {
  float frameDt = 1.0f / 30;  // s of simulated time per frame
  int stepsPerFrame = 4;      // the least LBM steps per frame; see lbmStepsPerFrame()
};

// Acceleration along "up" (= -gravity direction): temperature·T + density·ρ.
struct Buoyancy {
  float temperature = 0;  // m/s² per unit temperature
  float density = 0;      // m/s² per unit density; negative: heavy smoke sinks
};

// How obstacles bounce populations back: from a wall half-way along every link to a solid cell, or from
// where the link crosses the obstacle's analytic surface (interpolated; meshes stay half-way).
enum class ObstacleBoundary { HalfWay, Interpolated };

// How the lattice stores its populations: 32-bit floats, or 16-bit floats holding (f_i − w_i) · 2¹⁴
// (lbm_lattice.glsl), half the memory and traffic; the arithmetic stays 32-bit either way.
enum class PopulationStorage { Fp32, Fp16 };

struct Fluid {
  // Exactly one of viscosity and reynolds is set; kinematicViscosity() resolves them.
  std::optional<float> viscosity;  // m²/s
  std::optional<float> reynolds;   // with referenceLength and referenceSpeed()
  float referenceLength = 0;       // m, only with reynolds
  float smagorinsky = 0.1f;
  float maxLatticeVelocity = 0.1f;  // lattice speed of the fastest inflow (at most)
  ObstacleBoundary obstacleBoundary = ObstacleBoundary::HalfWay;
  PopulationStorage populationStorage = PopulationStorage::Fp32;
  Buoyancy buoyancy;
  glm::vec3 gravity{0, -9.81f, 0};  // only its direction is used
  glm::vec3 bodyForce{0};           // m/s², a constant acceleration (e.g. a driving pressure gradient)
};

enum class BoundaryType { NoSlip, FreeSlip, Outflow, Periodic, Inflow };

// Uniform: the wind everywhere on an inflow face. Parabolic: the wind times 4s(1−s) across each
// tangential axis whose two faces are no_slip walls (s = position across, 0..1): the wind is the peak.
enum class InflowProfile { Uniform, Parabolic };

struct Boundaries {
  enum Face { XMinus, XPlus, YMinus, YPlus, ZMinus, ZPlus };
  std::array<BoundaryType, 6> faces{BoundaryType::Outflow, BoundaryType::Outflow, BoundaryType::NoSlip,
                                    BoundaryType::Outflow, BoundaryType::Outflow, BoundaryType::Outflow};
  glm::vec3 wind{0};  // m/s, imposed on inflow faces; zero when there are none
  InflowProfile inflowProfile = InflowProfile::Uniform;
};

struct InletDisk {
  glm::vec3 center{0};
  float radius = 0;
  glm::vec3 normal{0, 1, 0};  // the side the flow leaves on
};

struct InletBox {
  glm::vec3 min{0};
  glm::vec3 max{0};
};

struct Inlet {
  std::variant<InletDisk, InletBox> shape;
  glm::vec3 velocity{0};  // m/s; a disk's is its speed along the normal
  float density = 1;
  float temperature = 0;
  float start = 0;                                      // s
  float stop = std::numeric_limits<float>::infinity();  // s, after start
  float noise = 0;                                      // 0..1, turbulence of the inflow
};

struct SphereObstacle {
  glm::vec3 center{0};
  float radius = 0;
};

struct CylinderObstacle {
  glm::vec3 center{0};
  float radius = 0;
  float height = 0;  // full length along the axis, centred on center
  glm::vec3 axis{0, 1, 0};
};

// A cylinder with hemispherical caps (a character's collider): the points within `radius` of the segment of
// length height − 2·radius along `axis` through `center`.
struct CapsuleObstacle {
  glm::vec3 center{0};
  float radius = 0;
  float height = 0;  // full length along the axis, caps included; at least 2·radius
  glm::vec3 axis{0, 1, 0};
};

struct BoxObstacle {
  glm::vec3 center{0};
  glm::vec3 size{0};  // full edge lengths
};

// world = translate + R(rotateDeg) · (scale · object), R = Rz·Ry·Rx (x applied first).
struct MeshObstacle {
  std::filesystem::path file;  // absolute, exists
  float scale = 1;
  glm::vec3 translate{0};
  glm::vec3 rotateDeg{0};
  // An engine's mesh held in memory: its triangles in place of `file`'s, and its rotation in place of
  // rotateDeg's.
  std::shared_ptr<const io::Mesh> data;
  std::optional<glm::mat3> rotation;
};

struct Keyframe {
  float time = 0;  // s
  glm::vec3 position{0};
};

// Position = linear interpolation of the keyframes, held at the ends (or repeated, with loop).
// It is the centre of a shape and the translation of a mesh; the shape's own centre/translate
// holds the first keyframe's position.
struct Motion {
  std::vector<Keyframe> keyframes;  // ≥ 2, strictly increasing time
  bool loop = false;
};

struct Obstacle {
  std::variant<SphereObstacle, CylinderObstacle, BoxObstacle, MeshObstacle, CapsuleObstacle> shape;
  std::optional<Motion> motion;
  bool shadows = true;  // casts shadows on the smoke
};

struct EmissionKey {
  float temperature = 0;
  glm::vec3 color{0};
};

struct Emission {
  std::vector<EmissionKey> ramp;  // strictly increasing temperature; ≥ 2 keys when present
  float intensity = 0;            // 0: no emission
};

struct Smoke {
  float extinction = 20;  // σ_t per unit density, 1/m
  float albedo = 0.9f;
  float phaseG = 0.2f;    // Henyey–Greenstein
  float dissipation = 0;  // 1/s
  // The simulation's sparse transport (sim::SmokeSettings): skip regions whose values are all ≤ the
  // threshold.
  bool sparse = true;
  float sparseThreshold = 1e-6f;
  Emission emission;
};

struct CameraOrbit {
  float degreesPerFrame = 0;  // about target, around the camera's up
};

struct CameraDolly {
  glm::vec3 endPosition{0};
  int frames = 1;  // frames to go from position to endPosition, then it stays
};

struct Camera {
  glm::vec3 position{0};
  glm::vec3 target{0};
  glm::vec3 up{0, 1, 0};
  float fovDeg = 40;  // vertical
  std::optional<std::variant<CameraOrbit, CameraDolly>> path;
};

struct DirectionalLight {
  glm::vec3 direction{0, 1, 0};  // from the shaded point toward the light
};

struct PointLight {
  glm::vec3 position{0};
};

// A point light's position turns about the line (center, axis); a directional light's direction
// turns about axis.
struct LightOrbit {
  glm::vec3 center{0};
  glm::vec3 axis{0, 1, 0};
  float degreesPerFrame = 0;
};

struct Light {
  std::variant<DirectionalLight, PointLight> source;
  glm::vec3 color{1};
  // Directional: irradiance (π matches the bake normalisation). Point: intensity, irradiance I/r².
  float intensity = std::numbers::pi_v<float>;
  bool shadows = true;
  std::optional<LightOrbit> path;
};

struct AmbientColor {
  glm::vec3 color{0};
};

// L1 spherical harmonics of the ambient light, per colour channel.
struct AmbientSh {
  std::array<glm::vec3, 4> coefficients{};  // L0, L1x, L1y, L1z
};

using Ambient = std::variant<AmbientColor, AmbientSh>;

enum class GuideLight { Front, Top, Bottom, Left, Right, Back };

// How `sixway render` turns a linear HDR frame into its 8-bit PNG (the EXR stays linear): Clamp cuts at 1,
// Aces applies a filmic curve (app/tone_map.h).
enum class ToneMap { Clamp, Aces };

struct RenderSettings {
  int width = 256;
  int height = 256;
  int lightmapSize = 128;  // multiple of 16
  float guideStepVoxels = 3;
  float guideAlphaStepVoxels = 0;  // > 0: the guide's channel A holds a fine alpha march of this step
  std::vector<GuideLight> guideLights{GuideLight::Front, GuideLight::Top, GuideLight::Bottom};
  glm::vec3 background{0};
  float shellThreshold = 0.1f;  // alpha at which the smoke shell depth is taken
  std::uint32_t seed = 1;
  // `sixway render` only: frames simulated (or played back) before the first one written, and the PNG's
  // display transform.
  int warmupFrames = 0;
  ToneMap toneMap = ToneMap::Clamp;
  float exposureStops = 0;  // the linear frame is scaled by 2^exposureStops before the tone map
};

// VdbSource::voxels for cells of the files' own voxel size ("voxels": "native").
inline constexpr int kNativeVoxels = 0;
// The most cells along a VDB playback lattice's longest axis.
inline constexpr int kMaxVdbVoxels = 1024;

// Which way is up in a VDB file's world: "y" (Houdini, EmberGen) or "z" (Blender).
enum class VdbUp { Y, Z };

// A scene that plays OpenVDB files back instead of simulating. Frame i is file ⌊i / framesPerFile⌋; the
// files are resampled onto one lattice of cubic cells that covers every file's active voxels.
// world = translate + scale · U(p), U = identity (up y) or (x, y, z) → (x, z, −y) (up z: a −90° turn about
// x).
struct VdbSource {
  std::vector<std::filesystem::path> files;  // absolute, each exists
  std::string densityGrid = "density";
  std::optional<std::string> temperatureGrid;  // the emission's temperature; none: no emission source
  float densityScale = 1;                      // multiplies the density grid's values
  int framesPerFile = 1;
  // Cells along the longest axis of the files' active box, or kNativeVoxels: the files' own voxel size.
  int voxels = 128;
  // The world box the lattice covers (min, max); none: the box of the files' active voxels.
  std::optional<std::pair<glm::vec3, glm::vec3>> box;
  float scale = 1;
  glm::vec3 translate{0};
  VdbUp up = VdbUp::Y;
};

struct Scene {
  std::string name;
  // With vdb, grid is the playback lattice, filled in when the files are opened (modes/scene_source.h);
  // fluid, boundaries, inlets and obstacles are empty.
  std::optional<VdbSource> vdb;
  Grid grid;
  TimeStepping time;
  Fluid fluid;
  Boundaries boundaries;
  std::vector<Inlet> inlets;
  std::vector<Obstacle> obstacles;
  Smoke smoke;
  Camera camera;
  std::vector<Light> lights;
  std::optional<Ambient> ambient;
  RenderSettings render;
};

// `sourceName` names the file in errors; mesh paths are resolved against `baseDir`.
// Throws InputError for anything the format does not allow.
Scene parseScene(const nlohmann::json& j, std::string_view sourceName, const std::filesystem::path& baseDir);
Scene loadScene(const std::filesystem::path& file);
// A scene file's text held in memory, named `name` in errors; relative paths (meshes, VDB files) from
// `baseDir`.
Scene parseSceneText(std::string_view text, const std::string& name, const std::filesystem::path& baseDir);
// Frames a scene can give: unbounded for a simulation, files · frames_per_file for VDB playback.
int sceneFrameCount(const Scene& scene);
// Throws InputError naming `source` when the scene plays VDB files back: what simulates refuses it.
void requireSimulated(const Scene& scene, std::string_view source);

}  // namespace sixway::scene
