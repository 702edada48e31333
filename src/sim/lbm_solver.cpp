#include "sim/lbm_solver.h"

#include <algorithm>
#include <string>

#include "gpu/context.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "sim/sim_params.h"
#include "sim/sim_spec.h"

namespace sixway::sim {
namespace {

constexpr uint32_t kGroupSize = 64;
constexpr uint32_t kPopulationsPerBuffer = 5;  // lbm_lattice.glsl

using gpu::BindingType;

struct StepPush {  // lbm_step.comp, lbm_keep_away.comp
  uint32_t slot, unused[3];
  glm::ivec4 boxMin, boxSize;
};
struct ForcesPush {  // forces.comp
  uint32_t step, slot, unused[2];
  glm::ivec4 boxMin, boxSize;
};

// The shader, or its LBM_FP16 variant (shaders/sim/shaders.cmake).
std::string latticeShader(const std::string& name, scene::PopulationStorage storage) {
  return storage == scene::PopulationStorage::Fp16 ? name + ":LBM_FP16" : name;
}

std::vector<BindingType> storageBuffers(int count) {
  return std::vector<BindingType>(count, BindingType::StorageBuffer);
}

// What every shader of the in-place lattice needs: its size and faces (the ghost layers, lbm_in_place.glsl).
gpu::SpecConstants storageSpec(const LbmSettings& settings) {
  gpu::SpecConstants constants;
  for (int a = 0; a < 3; ++a) constants.set(spec::kSize[a], settings.size[a]);
  for (int f = 0; f < 6; ++f) constants.set(spec::kFaces[f], uint32_t(settings.faces[f]));
  return constants;
}

// What lbm_step.comp and forces.comp share besides: the obstacles' boundary rule.
gpu::SpecConstants latticeSpec(const LbmSettings& settings) {
  return storageSpec(settings).set(spec::kInterpolatedBounceBack, settings.interpolatedBounceBack);
}

// A shader of the lattice, in the variant of its population storage, with `bindings` storage buffers.
gpu::ComputePipelineDesc latticeDesc(const std::string& shader, const LbmSettings& settings, int bindings,
                                     uint32_t pushConstantBytes, gpu::SpecConstants spec) {
  gpu::ComputePipelineDesc desc;
  desc.shader = latticeShader(shader, settings.storage);
  desc.bindings = storageBuffers(bindings);
  desc.pushConstantBytes = pushConstantBytes;
  desc.spec = std::move(spec);
  return desc;
}

}  // namespace

uint32_t populationBytes(scene::PopulationStorage storage) {
  return storage == scene::PopulationStorage::Fp16 ? 2 : 4;
}

uint32_t bytesPerCellUpdate(scene::PopulationStorage storage) {
  return 19 * populationBytes(storage) * 2 + 4 + 16 * 2;
}

glm::ivec3 storedSize(glm::ivec3 size, const std::array<scene::BoundaryType, 6>& faces) {
  for (int a = 0; a < 3; ++a)
    if (faces[2 * a] != scene::BoundaryType::Periodic) size[a] += 2;
  return size;
}

uint64_t latticeBytes(glm::ivec3 size, const std::array<scene::BoundaryType, 6>& faces,
                      scene::PopulationStorage storage) {
  const glm::ivec3 stored = storedSize(size, faces);
  return uint64_t(stored.x) * uint64_t(stored.y) * uint64_t(stored.z) * 19 * populationBytes(storage) +
         uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z) * 16;
}

LbmSettings lbmSettings(const scene::Scene& scene, const LatticeUnits& units) {
  LbmSettings s;
  s.size = scene.grid.size;
  s.faces = scene.boundaries.faces;
  s.tau = units.tau;
  s.smagorinsky = scene.fluid.smagorinsky;
  s.smokeUpres = scene.grid.smokeUpres;
  s.buoyancyTemperature = scene.fluid.buoyancy.temperature * units.accelerationScale;
  s.buoyancyDensity = scene.fluid.buoyancy.density * units.accelerationScale;
  s.up = -glm::normalize(scene.fluid.gravity);
  s.bodyForce = units.toLatticeAcceleration(scene.fluid.bodyForce);
  s.wind = units.toLatticeVelocity(scene.boundaries.wind);
  s.parabolicInflow = scene.boundaries.inflowProfile == scene::InflowProfile::Parabolic;
  s.interpolatedBounceBack = scene.fluid.obstacleBoundary == scene::ObstacleBoundary::Interpolated;
  s.storage = scene.fluid.populationStorage;
  return s;
}

ParityPipelines::ParityPipelines(const gpu::Context& context, const gpu::PipelineCache& cache,
                                 gpu::ComputePipelineDesc desc)
    : context_(&context), cache_(&cache), desc_(std::move(desc)) {}

const gpu::Pipeline& ParityPipelines::operator[](int parity) {
  if (!built_[parity]) {
    gpu::ComputePipelineDesc desc = desc_;
    desc.spec.set(spec::kParity, uint32_t(parity));
    built_[parity] = std::make_unique<gpu::Pipeline>(*context_, *cache_, desc);
  }
  return *built_[parity];
}

LbmSolver::LbmSolver(const gpu::Context& context, const gpu::PipelineCache& cache,
                     const LbmSettings& settings)
    : context_(&context),
      settings_(settings),
      cells_(uint64_t(settings.size.x) * settings.size.y * settings.size.z),
      storedSize_(sim::storedSize(settings.size, settings.faces)) {
  const uint64_t storedCells = uint64_t(storedSize_.x) * uint64_t(storedSize_.y) * uint64_t(storedSize_.z);
  if (storedCells > UINT32_MAX / kPopulationsPerBuffer)
    throw io::InputError("grid.size", "the lattice has too many cells for 32-bit population addressing");
  if (settings.storage == scene::PopulationStorage::Fp16 && !context.capabilities().storage16Bit)
    throw io::InputError(
        "fluid.population_storage",
        "fp16 needs 16-bit storage buffers (storageBuffer16BitAccess), which this device lacks");
  const std::string shape = std::to_string(settings.size.x) + "x" + std::to_string(settings.size.y) + "x" +
                            std::to_string(settings.size.z);
  // Zeroed by gpu::Buffer: the ghost cells' slots that no step writes read as zero, not as old memory.
  lattice_ = populationBuffers(storedCells, "the " + shape + " lattice");
  macro_ = gpu::Buffer::storage(context, cells_ * 16, "the " + shape + " velocity field");
  away_.push_back(populationBuffers(1, "the obstacles' populations"));

  init_ = ParityPipelines(context, cache,
                          latticeDesc("sim/lbm_init.comp", settings, 5, 0, storageSpec(settings)));
  keepAway_ = ParityPipelines(
      context, cache,
      latticeDesc("sim/lbm_keep_away.comp", settings, 10, sizeof(StepPush), storageSpec(settings)));

  gpu::ComputePipelineDesc step =
      latticeDesc("sim/lbm_step.comp", settings, 12, sizeof(StepPush), latticeSpec(settings));
  step.spec.set(spec::kTau0, settings.tau).set(spec::kSmagorinsky, settings.smagorinsky);
  step.spec.set(spec::kSmokeUpres, settings.smokeUpres);
  step.spec.set(spec::kBuoyancyTemperature, settings.buoyancyTemperature)
      .set(spec::kBuoyancyDensity, settings.buoyancyDensity);
  for (int a = 0; a < 3; ++a) {
    step.spec.set(spec::kUp[a], settings.up[a]).set(spec::kBody[a], settings.bodyForce[a]);
    step.spec.set(spec::kWind[a], settings.wind[a]);
  }
  step.spec.set(spec::kParabolicInflow, settings.parabolicInflow);
  step_ = ParityPipelines(context, cache, step);  // the interior (BOUNDARY_CELLS false)
  gpu::ComputePipelineDesc boundary = step;
  boundary.spec.set(spec::kBoundaryCells, true);
  stepBoundary_ = ParityPipelines(context, cache, boundary);
  gpu::ComputePipelineDesc faces = boundary;
  faces.spec.set(spec::kBoundaryObstacles, false);
  stepFaces_ = ParityPipelines(context, cache, faces);
  gpu::ComputePipelineDesc obstacles = boundary;
  obstacles.spec.set(spec::kBoundaryFaces, false);
  stepObstacles_ = ParityPipelines(context, cache, obstacles);
  gpu::ComputePipelineDesc uncovered = boundary;
  uncovered.spec.set(spec::kUncoveredCells, true);
  stepUncovered_ = ParityPipelines(context, cache, uncovered);

  forces_ = ParityPipelines(
      context, cache, latticeDesc("sim/forces.comp", settings, 8, sizeof(ForcesPush), latticeSpec(settings)));
}

std::array<gpu::Buffer, 4> LbmSolver::populationBuffers(uint64_t cells, const std::string& name) const {
  std::array<gpu::Buffer, 4> buffers;
  for (uint32_t b = 0; b < 4; ++b) {
    const uint32_t populations = b < 3 ? kPopulationsPerBuffer : 19 - 3 * kPopulationsPerBuffer;
    buffers[b] =
        gpu::Buffer::storage(*context_, uint64_t(populations) * cells * populationBytes(settings_.storage),
                             name + " (populations " + std::to_string(b * 5) + "..)");
  }
  return buffers;
}

const std::array<gpu::Buffer, 4>& LbmSolver::awayBuffers(uint64_t boxCells) {
  const uint64_t capacity =
      away_.back()[0].size() / (kPopulationsPerBuffer * populationBytes(settings_.storage));
  // Doubling, up to a lattice's worth: few buffers however the box grows, none beyond the lattice's limits.
  if (capacity < boxCells)
    away_.push_back(
        populationBuffers(std::min(std::max(boxCells, 2 * capacity), cells_), "the obstacles' populations"));
  return away_.back();
}

void LbmSolver::initialize(const std::vector<glm::vec4>& macro, int parity) {
  if (macro.size() != cells_)
    throw std::invalid_argument("LbmSolver::initialize: " + std::to_string(macro.size()) +
                                " cells given, the lattice has " + std::to_string(cells_));
  macro_.upload(macro);
  gpu::Sequence sequence(*context_);
  const auto& f = lattice_;
  sequence.dispatchLinear(
      init_[parity],
      {gpu::reads(macro_), gpu::writes(f[0]), gpu::writes(f[1]), gpu::writes(f[2]), gpu::writes(f[3])},
      std::span<const std::byte>(), cells_, kGroupSize);
  sequence.submit();
}

void LbmSolver::recordStep(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                           const gpu::Buffer& smoke, uint32_t slot, int parity,
                           const std::pair<glm::ivec3, glm::ivec3>& box) {
  const auto& f = lattice_;
  const glm::ivec3 boxSize = box.second - box.first;
  const uint64_t boxCells = uint64_t(boxSize.x) * uint64_t(boxSize.y) * uint64_t(boxSize.z);
  const bool keepAway = settings_.interpolatedBounceBack && boxCells > 0;
  const auto& away = keepAway ? awayBuffers(boxCells) : away_.back();
  const StepPush push{slot, {}, glm::ivec4(box.first, 0), glm::ivec4(boxSize, 0)};
  if (keepAway)
    sequence.dispatchLinear(keepAway_[parity],
                            {gpu::reads(f[0]), gpu::reads(f[1]), gpu::reads(f[2]), gpu::reads(f[3]),
                             gpu::writes(away[0]), gpu::writes(away[1]), gpu::writes(away[2]),
                             gpu::writes(away[3]), gpu::reads(params), gpu::reads(flags)},
                            push, boxCells, kGroupSize);
  const std::vector<gpu::Binding> bindings{
      gpu::reads(params),     gpu::reads(flags),      gpu::readsWrites(f[0]),   gpu::readsWrites(f[1]),
      gpu::readsWrites(f[2]), gpu::readsWrites(f[3]), gpu::readsWrites(macro_), gpu::reads(smoke),
      gpu::reads(away[0]),    gpu::reads(away[1]),    gpu::reads(away[2]),      gpu::reads(away[3])};
  // The cells lbm_step.comp's pipelines visit (cellVisited there): the interior box, the face slabs across
  // each axis and the obstacles' swept box.
  const glm::ivec3 size = settings_.size;
  uint64_t interior = 1, slabs = 0;
  bool boxOnFace = false;  // a cell of the box on a face slab: a slab cell may border an obstacle
  for (int a = 0; a < 3; ++a) {
    const bool oneCellPeriodic = size[a] == 1 && settings_.faces[2 * a] == scene::BoundaryType::Periodic;
    interior *= uint64_t(std::max(size[a] - (oneCellPeriodic ? 0 : 2), 0));
    if (!oneCellPeriodic) slabs += cells_ / uint64_t(size[a]) * (size[a] > 1 ? 2 : 1);
    if (!oneCellPeriodic && boxCells > 0)
      boxOnFace = boxOnFace || box.first[a] < 1 || box.second[a] > size[a] - 1;
  }
  // A lattice at most two cells deep along a walled axis has no interior, a periodic 1×1×1 one no face slabs.
  if (interior > 0) sequence.dispatchLinear(step_[parity], bindings, push, interior, kGroupSize);
  if (boxOnFace) {
    sequence.dispatchLinear(stepBoundary_[parity], bindings, push, slabs + boxCells, kGroupSize);
  } else {
    if (slabs > 0) sequence.dispatchLinear(stepFaces_[parity], bindings, push, slabs, kGroupSize);
    if (boxCells > 0) sequence.dispatchLinear(stepObstacles_[parity], bindings, push, boxCells, kGroupSize);
  }
  // Last: the cells uncovered this step overwrite slots their neighbours have read back by now.
  if (boxCells > 0) sequence.dispatchLinear(stepUncovered_[parity], bindings, push, boxCells, kGroupSize);
}

void LbmSolver::recordForces(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                             uint32_t slot, int parity, const gpu::Buffer& forces,
                             const std::pair<glm::ivec3, glm::ivec3>& box) {
  const auto& f = lattice_;
  const glm::ivec3 size = box.second - box.first;
  const uint64_t cells = uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z);
  sequence.dispatchLinear(forces_[parity],
                          {gpu::reads(params), gpu::reads(flags), gpu::reads(f[0]), gpu::reads(f[1]),
                           gpu::reads(f[2]), gpu::reads(f[3]), gpu::reads(macro_), gpu::readsWrites(forces)},
                          ForcesPush{slot, slot, {}, glm::ivec4(box.first, 0), glm::ivec4(size, 0)}, cells,
                          kGroupSize);
}

}  // namespace sixway::sim
