#pragma once
// The smoke (density and temperature) on a grid SMOKE_UPRES times finer than the lattice:
// sources and dissipation, then transport by the lattice velocity with flux-corrected transport
// (Zalesak 1979; shaders/sim/fct_*.comp): conservative, non-negative, and free of new extrema.
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "io/scene.h"

namespace sixway::gpu {
class Sequence;
}

namespace sixway::sim {

struct SmokeSettings {
  glm::ivec3 lattice{0};
  int upres = 1;
  std::array<io::BoundaryType, 6> faces{};
  float decayPerStep = 1;  // exp(−dissipation · dt)
};

class SmokeTransport {
 public:
  SmokeTransport(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSettings& settings);

  // The GPU-timed stages these record, one per pass (Simulation sums them per name).
  static constexpr const char* kSourcesStage = "smoke sources";
  static constexpr const char* kFluxesStage = "smoke fluxes";
  static constexpr const char* kLimiterStage = "smoke limiter";
  static constexpr const char* kUpdateStage = "smoke update";

  // Inlet cells take the inlet's values; elsewhere the smoke decays.
  void recordSources(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                     uint32_t slot) const;
  // Moves the smoke for one lattice step with the velocity in `macro` (cells/step, xyz of vec4),
  // in `upres` substeps so that the Courant number stays that of the lattice.
  void recordTransport(gpu::Sequence& sequence, const gpu::Buffer& flags, const gpu::Buffer& macro) const;

  // (density, temperature) per smoke cell, x fastest.
  const gpu::Buffer& smoke() const { return smoke_; }
  void upload(const std::vector<glm::vec2>& values);
  std::vector<glm::vec2> download() const { return smoke_.download<glm::vec2>(); }
  // Density and temperature into two float buffers of cells() values each (the renderers' layout).
  void recordExport(gpu::Sequence& sequence, const gpu::Buffer& density,
                    const gpu::Buffer& temperature) const;
  glm::ivec3 size() const { return settings_.lattice * settings_.upres; }
  int upres() const { return settings_.upres; }
  uint64_t cells() const { return cells_; }

 private:
  SmokeSettings settings_;
  uint64_t cells_;
  gpu::Buffer smoke_, lowOrder_, ratios_;
  std::array<gpu::Buffer, 3> antidiffusive_;  // per axis (sim_fct_fluxes.glsl)
  std::unique_ptr<gpu::Pipeline> sources_, fluxes_, limiter_, update_, export_;
};

}  // namespace sixway::sim
