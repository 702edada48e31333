#include "sim/smoke_transport.h"

#include <stdexcept>
#include <string>

#include "gpu/sequence.h"
#include "sim/sim_spec.h"

namespace sixway::sim {
namespace {

constexpr uint32_t kGroupSize = 64;

struct SourcesPush {
  uint32_t slot;
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
    d.spec.set(spec::kPeriodic[axis], s.faces[2 * axis] == io::BoundaryType::Periodic);
}

}  // namespace

SmokeTransport::SmokeTransport(const gpu::Context& context, const gpu::PipelineCache& cache,
                               const SmokeSettings& settings)
    : settings_(settings) {
  const glm::ivec3 s = size();
  cells_ = uint64_t(s.x) * s.y * s.z;
  const std::string shape = std::to_string(s.x) + "x" + std::to_string(s.y) + "x" + std::to_string(s.z);
  smoke_ = gpu::Buffer::storage(context, cells_ * 8, "the " + shape + " smoke grid");
  lowOrder_ = gpu::Buffer::storage(context, cells_ * 8, "the " + shape + " smoke grid (low-order update)");
  for (int a = 0; a < 3; ++a)  // one per axis (sim_fct_fluxes.glsl)
    antidiffusive_[a] =
        gpu::Buffer::storage(context, cells_ * 8, "the " + shape + " smoke grid (" + "xyz"[a] + " fluxes)");
  ratios_ = gpu::Buffer::storage(context, cells_ * 16, "the " + shape + " smoke grid (limiters)");

  gpu::ComputePipelineDesc sources = smokeDesc("sim/smoke_sources.comp", 3, settings);
  sources.spec.set(spec::kDecay, settings.decayPerStep);
  sources.pushConstantBytes = sizeof(SourcesPush);
  sources_ = std::make_unique<gpu::Pipeline>(context, cache, sources);

  gpu::ComputePipelineDesc fluxes = smokeDesc("sim/fct_fluxes.comp", 7, settings);
  for (int f = 0; f < 6; ++f) fluxes.spec.set(spec::kFaces[f], uint32_t(settings.faces[f]));
  fluxes_ = std::make_unique<gpu::Pipeline>(context, cache, fluxes);

  gpu::ComputePipelineDesc limiter = smokeDesc("sim/fct_limiter.comp", 7, settings);
  setPeriodicAxes(limiter, settings);
  limiter_ = std::make_unique<gpu::Pipeline>(context, cache, limiter);

  gpu::ComputePipelineDesc update = smokeDesc("sim/fct_update.comp", 6, settings);
  setPeriodicAxes(update, settings);
  update_ = std::make_unique<gpu::Pipeline>(context, cache, update);

  export_ = std::make_unique<gpu::Pipeline>(context, cache, smokeDesc("sim/smoke_export.comp", 3, settings));
}

void SmokeTransport::upload(const std::vector<glm::vec2>& values) {
  if (values.size() != cells_)
    throw std::invalid_argument("SmokeTransport::upload: " + std::to_string(values.size()) +
                                " values for a grid of " + std::to_string(cells_));
  smoke_.upload(values);
}

void SmokeTransport::recordSources(gpu::Sequence& sequence, const gpu::Buffer& params,
                                   const gpu::Buffer& flags, uint32_t slot) const {
  sequence.beginStage(kSourcesStage);
  sequence.dispatchLinear(*sources_, {gpu::reads(params), gpu::reads(flags), gpu::readsWrites(smoke_)},
                          SourcesPush{slot}, cells_, kGroupSize);
  sequence.endStage();
}

void SmokeTransport::recordTransport(gpu::Sequence& sequence, const gpu::Buffer& flags,
                                     const gpu::Buffer& macro) const {
  const std::span<const std::byte> none;
  for (int substep = 0; substep < settings_.upres; ++substep) {
    sequence.beginStage(kFluxesStage);
    sequence.dispatchLinear(
        *fluxes_,
        {gpu::reads(flags), gpu::reads(macro), gpu::reads(smoke_), gpu::writes(lowOrder_),
         gpu::writes(antidiffusive_[0]), gpu::writes(antidiffusive_[1]), gpu::writes(antidiffusive_[2])},
        none, cells_, kGroupSize);
    sequence.endStage();
    sequence.beginStage(kLimiterStage);
    sequence.dispatchLinear(
        *limiter_,
        {gpu::reads(flags), gpu::reads(smoke_), gpu::reads(lowOrder_), gpu::reads(antidiffusive_[0]),
         gpu::reads(antidiffusive_[1]), gpu::reads(antidiffusive_[2]), gpu::writes(ratios_)},
        none, cells_, kGroupSize);
    sequence.endStage();
    sequence.beginStage(kUpdateStage);
    sequence.dispatchLinear(
        *update_,
        {gpu::reads(lowOrder_), gpu::reads(antidiffusive_[0]), gpu::reads(antidiffusive_[1]),
         gpu::reads(antidiffusive_[2]), gpu::reads(ratios_), gpu::writes(smoke_)},
        none, cells_, kGroupSize);
    sequence.endStage();
  }
}

void SmokeTransport::recordExport(gpu::Sequence& sequence, const gpu::Buffer& density,
                                  const gpu::Buffer& temperature) const {
  sequence.dispatchLinear(*export_, {gpu::reads(smoke_), gpu::writes(density), gpu::writes(temperature)},
                          std::span<const std::byte>(), cells_, kGroupSize);
}

}  // namespace sixway::sim
