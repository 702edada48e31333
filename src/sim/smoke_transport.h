#pragma once
// The smoke (density and temperature) on a grid SMOKE_UPRES times finer than the lattice:
// sources and dissipation, then transport by the lattice velocity with flux-corrected transport
// (Zalesak 1979; shaders/sim/fct_*.comp): conservative, non-negative, and free of new extrema.
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Sequence;
}

namespace sixway::sim {

struct SmokeSettings {
  glm::ivec3 lattice{0};
  int upres = 1;
  std::array<scene::BoundaryType, 6> faces{};
  float decayPerStep = 1;  // exp(−dissipation · dt)
  // Skip the bricks of 16×2×2 cells whose values and neighbours' are all ≤ sparseThreshold, dropping those
  // values (shaders/common/sim_bricks.glsl); false: every cell every substep.
  bool sparse = true;
  float sparseThreshold = 1e-6f;
};

class SmokeTransport {
 public:
  SmokeTransport(const gpu::Context& context, const gpu::PipelineCache& cache, const SmokeSettings& settings);

  // The GPU-timed stages these record, one per pass (Simulation sums them per name).
  static constexpr const char* kSourcesStage = "smoke sources";
  static constexpr const char* kActivityStage = "smoke activity";  // sparse transport only
  static constexpr const char* kFluxesStage = "smoke fluxes";
  static constexpr const char* kLimiterStage = "smoke limiter";
  static constexpr const char* kUpdateStage = "smoke update";

  // Inlet cells take the inlet's values; elsewhere the smoke decays. `inlets`: lattice cells [min, max) that
  // hold every inlet cell (ObstacleSet::inletBox; the sparse transport looks for inlet cells only there).
  void recordSources(gpu::Sequence& sequence, const gpu::Buffer& params, const gpu::Buffer& flags,
                     uint32_t slot, const std::pair<glm::ivec3, glm::ivec3>& inlets) const;
  // Moves the smoke for one lattice step with the velocity in `macro` (cells/step, xyz of vec4),
  // in `upres` substeps so that the Courant number stays that of the lattice. Stages per substep: the
  // activity (the sparse transport's brick lists) and the three FCT passes.
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
  uint32_t stagesPerStep() const { return uint32_t(settings_.upres) * (settings_.sparse ? 4 : 3) + 1; }
  // The bricks active in the last substep (sim_bricks.glsl), and all of them; every brick when dense.
  uint64_t activeBricks() const;
  uint64_t bricks() const { return bricks_; }

 private:
  SmokeSettings settings_;
  uint64_t cells_, bricks_;
  glm::ivec3 brickGroups_;
  gpu::Buffer smoke_, lowOrder_, ratios_;
  gpu::Buffer activity_, brickHeader_, activeList_, clearList_;  // the sparse transport's (sim_bricks.glsl)
  std::array<gpu::Buffer, 3> antidiffusive_;                     // per axis (sim_fct_fluxes.glsl)
  std::unique_ptr<gpu::Pipeline> sources_, decay_, activityPass_, clear_, fluxes_, limiter_, update_, export_;
};

}  // namespace sixway::sim
