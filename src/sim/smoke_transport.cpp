#include "sim/smoke_transport.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "gpu/sequence.h"
#include "sim/sim_spec.h"

namespace sixway::sim {
namespace {

constexpr uint32_t kGroupSize = 64;
constexpr glm::ivec3 kBrick{16, 2, 2};  // cells: the FCT passes' workgroup (sim_bricks.glsl)
constexpr uint32_t kBrickActive = 1;
// The brick header's words (sim_bricks.glsl): the two lists' indirect dispatches, then their lengths.
constexpr uint64_t kActiveDispatchOffset = 0, kClearDispatchOffset = 12;
constexpr size_t kActiveCountWord = 6, kHeaderWords = 8;
constexpr uint32_t kBrickListRow = 32768;  // workgroups per row of a list's dispatch

struct SourcesPush {  // smoke_sources.comp
  uint32_t slot;
  uint32_t unused[3];
  glm::ivec4 boxMin, boxSize;  // the sparse transport's inlet box, smoke cells
};

gpu::ComputePipelineDesc smokeDesc(const char* shader, int bindings, const SmokeSettings& s) {
  gpu::ComputePipelineDesc d;
  d.shader = shader;
  d.bindings.assign(bindings, gpu::BindingType::StorageBuffer);
  for (int a = 0; a < 3; ++a) d.spec.set(spec::kSize[a], s.lattice[a]);
  d.spec.set(spec::kSmokeUpres, s.upres);
  return d;
}

void setPeriodicAxes(gpu::ComputePipelineDesc& d, const SmokeSettings& s) {
  for (int axis = 0; axis < 3; ++axis)
    d.spec.set(spec::kPeriodic[axis], s.faces[2 * axis] == scene::BoundaryType::Periodic);
}

// An FCT pass: its own bindings, then the brick header and the active list (sim_fct_cell.glsl).
gpu::ComputePipelineDesc fctDesc(const char* shader, int ownBindings, const SmokeSettings& s) {
  gpu::ComputePipelineDesc d = smokeDesc(shader, ownBindings + 2, s);
  d.spec.set(spec::kSparse, s.sparse);
  return d;
}

}  // namespace

SmokeTransport::SmokeTransport(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const SmokeSettings& settings)
    : settings_(settings) {
  const glm::ivec3 s = size();
  cells_ = uint64_t(s.x) * s.y * s.z;
  brickGroups_ = (s + kBrick - 1) / kBrick;
  bricks_ = uint64_t(brickGroups_.x) * brickGroups_.y * brickGroups_.z;
  const std::string shape = std::to_string(s.x) + "x" + std::to_string(s.y) + "x" + std::to_string(s.z);
  const auto grid = [&](const std::string& what) { return "the " + shape + " smoke grid" + what; };
  smoke_ = gpu::Buffer::storage(context, cells_ * 8, grid(""));
  lowOrder_ = gpu::Buffer::storage(context, cells_ * 8, grid(" (low-order update)"));
  for (int a = 0; a < 3; ++a)  // one per axis (sim_fct_fluxes.glsl)
    antidiffusive_[a] =
        gpu::Buffer::storage(context, cells_ * 8, grid(std::string(" (") + "xyz"[a] + " fluxes)"));
  ratios_ = gpu::Buffer::storage(context, cells_ * 16, grid(" (limiters)"));
  activity_ = gpu::Buffer::storage(context, bricks_ * 4, grid(" (brick activity)"));
  brickHeader_ = gpu::Buffer(context, kHeaderWords * 4,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             gpu::MemoryKind::Device, grid(" (brick lists)"));
  activeList_ = gpu::Buffer::storage(context, bricks_ * 4, grid(" (active bricks)"));
  clearList_ = gpu::Buffer::storage(context, bricks_ * 4, grid(" (cleared bricks)"));

  gpu::ComputePipelineDesc sources = smokeDesc("sim/smoke_sources.comp", 3, settings);
  sources.spec.set(spec::kDecay, settings.decayPerStep).set(spec::kSparse, settings.sparse);
  sources.pushConstantBytes = sizeof(SourcesPush);
  sources_ = std::make_unique<gpu::Pipeline>(context, cache, sources);
  if (settings.sparse && settings.decayPerStep != 1) {
    gpu::ComputePipelineDesc decay = smokeDesc("sim/smoke_decay.comp", 3, settings);
    decay.spec.set(spec::kDecay, settings.decayPerStep);
    decay_ = std::make_unique<gpu::Pipeline>(context, cache, decay);
  }

  if (settings.sparse) {
    gpu::ComputePipelineDesc activity = smokeDesc("sim/smoke_activity.comp", 5, settings);
    setPeriodicAxes(activity, settings);
    activity.spec.set(spec::kSparseThreshold, settings.sparseThreshold);
    activityPass_ = std::make_unique<gpu::Pipeline>(context, cache, activity);
    clear_ = std::make_unique<gpu::Pipeline>(context, cache, smokeDesc("sim/smoke_clear.comp", 8, settings));
  }

  gpu::ComputePipelineDesc fluxes = fctDesc("sim/fct_fluxes.comp", 7, settings);
  for (int f = 0; f < 6; ++f) fluxes.spec.set(spec::kFaces[f], uint32_t(settings.faces[f]));
  fluxes_ = std::make_unique<gpu::Pipeline>(context, cache, fluxes);

  gpu::ComputePipelineDesc limiter = fctDesc("sim/fct_limiter.comp", 7, settings);
  setPeriodicAxes(limiter, settings);
  limiter_ = std::make_unique<gpu::Pipeline>(context, cache, limiter);

  gpu::ComputePipelineDesc update = fctDesc("sim/fct_update.comp", 6, settings);
  setPeriodicAxes(update, settings);
  update_ = std::make_unique<gpu::Pipeline>(context, cache, update);

  export_ = std::make_unique<gpu::Pipeline>(context, cache, smokeDesc("sim/smoke_export.comp", 3, settings));
}

void SmokeTransport::upload(const std::vector<glm::vec2>& values) {
  if (values.size() != cells_)
    throw std::invalid_argument("SmokeTransport::upload: " + std::to_string(values.size()) +
                                " values for a grid of " + std::to_string(cells_));
  smoke_.upload(values);
  // Every brick counts as active in the last substep: the next step's dissipation reaches all of them, and
  // its activity pass drops the values of the bricks it finds inactive.
  activity_.upload(std::vector<uint32_t>(bricks_, kBrickActive));
  std::vector<uint32_t> all(bricks_);
  std::iota(all.begin(), all.end(), 0u);
  activeList_.upload(all);
  const uint32_t count = uint32_t(bricks_);
  const std::vector<uint32_t> header{
      std::min(count, kBrickListRow), (count + kBrickListRow - 1) / kBrickListRow, 1, 0, 0, 0, count, 0};
  brickHeader_.upload(header);
}

uint64_t SmokeTransport::activeBricks() const {
  if (!settings_.sparse) return bricks_;
  return brickHeader_.download<uint32_t>()[kActiveCountWord];
}

void SmokeTransport::recordSources(gpu::Sequence& sequence, const gpu::Buffer& params,
                                   const gpu::Buffer& flags, uint32_t slot,
                                   const std::pair<glm::ivec3, glm::ivec3>& inlets) const {
  const std::vector<gpu::Binding> bindings{gpu::reads(params), gpu::reads(flags), gpu::readsWrites(smoke_)};
  sequence.beginStage(kSourcesStage);
  if (!settings_.sparse) {
    sequence.dispatchLinear(*sources_, bindings, SourcesPush{slot}, cells_, kGroupSize);
    sequence.endStage();
    return;
  }
  if (decay_)
    sequence.dispatchIndirect(*decay_,
                              {gpu::reads(brickHeader_), gpu::reads(activeList_), gpu::readsWrites(smoke_)},
                              std::span<const std::byte>(), brickHeader_, kActiveDispatchOffset);
  const glm::ivec3 first = glm::max(inlets.first, glm::ivec3(0)) * settings_.upres;
  const glm::ivec3 size =
      glm::max(glm::min(inlets.second, settings_.lattice) * settings_.upres - first, glm::ivec3(0));
  const uint64_t boxCells = uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z);
  if (boxCells > 0)
    sequence.dispatchLinear(*sources_, bindings,
                            SourcesPush{slot, {}, glm::ivec4(first, 0), glm::ivec4(size, 0)}, boxCells,
                            kGroupSize);
  sequence.endStage();
}

void SmokeTransport::recordTransport(gpu::Sequence& sequence, const gpu::Buffer& flags,
                                     const gpu::Buffer& macro) const {
  const std::span<const std::byte> none;
  const glm::uvec3 groups(brickGroups_);
  // An FCT pass over the active bricks (sparse) or all of them (dense).
  const auto fct = [&](const char* stage, const gpu::Pipeline& pass, std::vector<gpu::Binding> bindings) {
    bindings.push_back(gpu::reads(brickHeader_));
    bindings.push_back(gpu::reads(activeList_));
    sequence.beginStage(stage);
    if (settings_.sparse)
      sequence.dispatchIndirect(pass, bindings, none, brickHeader_, kActiveDispatchOffset);
    else
      sequence.dispatch(pass, bindings, none, groups.x, groups.y, groups.z);
    sequence.endStage();
  };
  for (int substep = 0; substep < settings_.upres; ++substep) {
    if (settings_.sparse) {
      sequence.beginStage(kActivityStage);
      sequence.fill(brickHeader_, 0);
      sequence.dispatchLinear(
          *activityPass_,
          {gpu::reads(smoke_), gpu::readsWrites(activity_), gpu::readsWrites(brickHeader_),
           gpu::writes(activeList_), gpu::writes(clearList_)},
          none, bricks_, kGroupSize);
      sequence.dispatchIndirect(
          *clear_,
          {gpu::reads(brickHeader_), gpu::reads(clearList_), gpu::writes(smoke_), gpu::writes(lowOrder_),
           gpu::writes(antidiffusive_[0]), gpu::writes(antidiffusive_[1]), gpu::writes(antidiffusive_[2]),
           gpu::writes(ratios_)},
          none, brickHeader_, kClearDispatchOffset);
      sequence.endStage();
    }
    fct(kFluxesStage, *fluxes_,
        {gpu::reads(flags), gpu::reads(macro), gpu::reads(smoke_), gpu::writes(lowOrder_),
         gpu::writes(antidiffusive_[0]), gpu::writes(antidiffusive_[1]), gpu::writes(antidiffusive_[2])});
    fct(kLimiterStage, *limiter_,
        {gpu::reads(flags), gpu::reads(smoke_), gpu::reads(lowOrder_), gpu::reads(antidiffusive_[0]),
         gpu::reads(antidiffusive_[1]), gpu::reads(antidiffusive_[2]), gpu::writes(ratios_)});
    fct(kUpdateStage, *update_,
        {gpu::reads(lowOrder_), gpu::reads(antidiffusive_[0]), gpu::reads(antidiffusive_[1]),
         gpu::reads(antidiffusive_[2]), gpu::reads(ratios_), gpu::writes(smoke_)});
  }
}

void SmokeTransport::recordExport(gpu::Sequence& sequence, const gpu::Buffer& density,
                                  const gpu::Buffer& temperature) const {
  sequence.dispatchLinear(*export_, {gpu::reads(smoke_), gpu::writes(density), gpu::writes(temperature)},
                          std::span<const std::byte>(), cells_, kGroupSize);
}

}  // namespace sixway::sim
