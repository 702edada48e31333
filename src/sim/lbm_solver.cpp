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

struct StepPush {  // lbm_step.comp
  uint32_t slot, unused[3];
  glm::ivec4 boxMin, boxSize;
};
struct ForcesPush {  // forces.comp
  uint32_t step, slot, unused[2];
  glm::ivec4 boxMin, boxSize;
};

// The shader, or its LBM_FP16 variant (shaders/sim/shaders.cmake).
std::string latticeShader(const std::string& name, io::PopulationStorage storage) {
  return storage == io::PopulationStorage::Fp16 ? name + ":LBM_FP16" : name;
}

std::vector<BindingType> storageBuffers(int count) {
  return std::vector<BindingType>(count, BindingType::StorageBuffer);
}

// What lbm_step.comp and forces.comp share: the lattice, its faces, the obstacles' boundary rule.
gpu::SpecConstants latticeSpec(const LbmSettings& settings) {
  gpu::SpecConstants constants;
  for (int a = 0; a < 3; ++a) constants.set(spec::kSize[a], settings.size[a]);
  for (int f = 0; f < 6; ++f) constants.set(spec::kFaces[f], uint32_t(settings.faces[f]));
  constants.set(spec::kInterpolatedBounceBack, settings.interpolatedBounceBack);
  return constants;
}

}  // namespace

uint32_t populationBytes(io::PopulationStorage storage) {
  return storage == io::PopulationStorage::Fp16 ? 2 : 4;
}

uint32_t bytesPerCellUpdate(io::PopulationStorage storage) {
  return 19 * populationBytes(storage) * 2 + 4 + 16 * 2;
}

uint64_t latticeBytes(uint64_t cells, io::PopulationStorage storage) {
  return cells * (2 * 19 * populationBytes(storage) + 16);
}

LbmSettings lbmSettings(const io::Scene& scene, const LatticeUnits& units) {
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
  s.parabolicInflow = scene.boundaries.inflowProfile == io::InflowProfile::Parabolic;
  s.interpolatedBounceBack = scene.fluid.obstacleBoundary == io::ObstacleBoundary::Interpolated;
  s.storage = scene.fluid.populationStorage;
  return s;
}

LbmSolver::LbmSolver(const gpu::Context& context, const gpu::PipelineCache& cache,
                     const LbmSettings& settings)
    : context_(&context),
      settings_(settings),
      cells_(uint64_t(settings.size.x) * settings.size.y * settings.size.z) {
  if (cells_ > UINT32_MAX / kPopulationsPerBuffer)
    throw io::InputError("grid.size", "the lattice has too many cells for 32-bit population addressing");
  if (settings.storage == io::PopulationStorage::Fp16 && !context.capabilities().storage16Bit)
    throw io::InputError(
        "fluid.population_storage",
        "fp16 needs 16-bit storage buffers (storageBuffer16BitAccess), which this device lacks");
  const std::string shape = std::to_string(settings.size.x) + "x" + std::to_string(settings.size.y) + "x" +
                            std::to_string(settings.size.z);
  for (int parity = 0; parity < 2; ++parity)
    for (uint32_t b = 0; b < 4; ++b) {
      const uint32_t populations = b < 3 ? kPopulationsPerBuffer : 19 - 3 * kPopulationsPerBuffer;
      lattices_[parity][b] =
          gpu::Buffer::storage(context, uint64_t(populations) * cells_ * populationBytes(settings.storage),
                               "the " + shape + " lattice (populations " + std::to_string(b * 5) + "..)");
    }
  macro_ = gpu::Buffer::storage(context, cells_ * 16, "the " + shape + " velocity field");

  gpu::ComputePipelineDesc init;
  init.shader = latticeShader("sim/lbm_init.comp", settings.storage);
  init.bindings = storageBuffers(5);
  init.spec.set(spec::kCells, uint32_t(cells_));
  init_ = std::make_unique<gpu::Pipeline>(context, cache, init);

  gpu::ComputePipelineDesc step;
  step.shader = latticeShader("sim/lbm_step.comp", settings.storage);
  step.bindings = storageBuffers(12);
  step.pushConstantBytes = sizeof(StepPush);
  step.spec = latticeSpec(settings);
  step.spec.set(spec::kTau0, settings.tau).set(spec::kSmagorinsky, settings.smagorinsky);
  step.spec.set(spec::kSmokeUpres, settings.smokeUpres);
  step.spec.set(spec::kBuoyancyTemperature, settings.buoyancyTemperature)
      .set(spec::kBuoyancyDensity, settings.buoyancyDensity);
  for (int a = 0; a < 3; ++a) {
    step.spec.set(spec::kUp[a], settings.up[a]).set(spec::kBody[a], settings.bodyForce[a]);
    step.spec.set(spec::kWind[a], settings.wind[a]);
  }
  step.spec.set(spec::kParabolicInflow, settings.parabolicInflow);
  step_ = std::make_unique<gpu::Pipeline>(context, cache, step);  // the interior (BOUNDARY_CELLS false)
  gpu::ComputePipelineDesc boundary = step;
  boundary.spec.set(spec::kBoundaryCells, true);
  stepBoundary_ = std::make_unique<gpu::Pipeline>(context, cache, boundary);
  gpu::ComputePipelineDesc faces = boundary;
  faces.spec.set(spec::kBoundaryObstacles, false);
  stepFaces_ = std::make_unique<gpu::Pipeline>(context, cache, faces);
  gpu::ComputePipelineDesc obstacles = boundary;
  obstacles.spec.set(spec::kBoundaryFaces, false);
  stepObstacles_ = std::make_unique<gpu::Pipeline>(context, cache, obstacles);

  gpu::ComputePipelineDesc forces;
  forces.shader = latticeShader("sim/forces.comp", settings.storage);
  forces.bindings = storageBuffers(8);
  forces.pushConstantBytes = sizeof(ForcesPush);
  forces.spec = latticeSpec(settings);
  forces_ = std::make_unique<gpu::Pipeline>(context, cache, forces);
}

void LbmSolver::initialize(const std::vector<glm::vec4>& macro, int parity) {
  if (macro.size() != cells_)
    throw std::invalid_argument("LbmSolver::initialize: " + std::to_string(macro.size()) +
                                " cells given, the lattice has " + std::to_string(cells_));
  macro_.upload(macro);
  gpu::Sequence sequence(*context_);
  const auto& f = lattices_[parity];
  sequence.dispatchLinear(
      *init_,
      {gpu::reads(macro_), gpu::writes(f[0]), gpu::writes(f[1]), gpu::writes(f[2]), gpu::writes(f[3])},
      std::span<const std::byte>(), cells_, kGroupSize);
  sequence.submit();
}

void LbmSolver::recordStep(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                           const gpu::Buffer& smoke, uint32_t slot, int parity,
                           const std::pair<glm::ivec3, glm::ivec3>& box) const {
  const auto& from = lattices_[parity];
  const auto& to = lattices_[1 - parity];
  const std::vector<gpu::Binding> bindings{gpu::reads(params),  gpu::reads(flags),        gpu::reads(from[0]),
                                           gpu::reads(from[1]), gpu::reads(from[2]),      gpu::reads(from[3]),
                                           gpu::writes(to[0]),  gpu::writes(to[1]),       gpu::writes(to[2]),
                                           gpu::writes(to[3]),  gpu::readsWrites(macro_), gpu::reads(smoke)};
  const glm::ivec3 boxSize = box.second - box.first;
  const StepPush push{slot, {}, glm::ivec4(box.first, 0), glm::ivec4(boxSize, 0)};
  // The cells lbm_step.comp's pipelines visit (cellVisited there): the interior box, the face slabs across
  // each axis and the obstacles' swept box.
  const glm::ivec3 size = settings_.size;
  const uint64_t boxCells = uint64_t(boxSize.x) * uint64_t(boxSize.y) * uint64_t(boxSize.z);
  uint64_t interior = 1, slabs = 0;
  bool boxOnFace = false;  // a cell of the box on a face slab: a slab cell may border an obstacle
  for (int a = 0; a < 3; ++a) {
    const bool oneCellPeriodic = size[a] == 1 && settings_.faces[2 * a] == io::BoundaryType::Periodic;
    interior *= uint64_t(std::max(size[a] - (oneCellPeriodic ? 0 : 2), 0));
    if (!oneCellPeriodic) slabs += cells_ / uint64_t(size[a]) * (size[a] > 1 ? 2 : 1);
    if (!oneCellPeriodic && boxCells > 0)
      boxOnFace = boxOnFace || box.first[a] < 1 || box.second[a] > size[a] - 1;
  }
  // A lattice at most two cells deep along a walled axis has no interior, a periodic 1×1×1 one no face slabs.
  if (interior > 0) sequence.dispatchLinear(*step_, bindings, push, interior, kGroupSize);
  if (boxOnFace) {
    sequence.dispatchLinear(*stepBoundary_, bindings, push, slabs + boxCells, kGroupSize);
    return;
  }
  if (slabs > 0) sequence.dispatchLinear(*stepFaces_, bindings, push, slabs, kGroupSize);
  if (boxCells > 0) sequence.dispatchLinear(*stepObstacles_, bindings, push, boxCells, kGroupSize);
}

void LbmSolver::recordForces(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                             uint32_t slot, int parity, const gpu::Buffer& forces,
                             const std::pair<glm::ivec3, glm::ivec3>& box) const {
  const auto& f = lattices_[parity];
  const glm::ivec3 size = box.second - box.first;
  const uint64_t cells = uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z);
  sequence.dispatchLinear(*forces_,
                          {gpu::reads(params), gpu::reads(flags), gpu::reads(f[0]), gpu::reads(f[1]),
                           gpu::reads(f[2]), gpu::reads(f[3]), gpu::reads(macro_), gpu::readsWrites(forces)},
                          ForcesPush{slot, slot, {}, glm::ivec4(box.first, 0), glm::ivec4(size, 0)}, cells,
                          kGroupSize);
}

}  // namespace sixway::sim
