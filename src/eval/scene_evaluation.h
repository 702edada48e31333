#pragma once
// One run of `sixway eval --scene` (scene_eval.h): the scene's frames rendered by every method and by the
// path tracer, measured frame by frame into the report's per-frame entries and into the totals of its
// summary.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/lightmap_metrics.h"
#include "eval/scene_eval.h"
#include "eval/temporal_change.h"
#include "io/image.h"
#include "metrics/image_metrics.h"
#include "modes/mode_renderer.h"
#include "render/camera.h"
#include "render/obstacle_bvh.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::gpu {
class Context;
class PipelineCache;
}  // namespace sixway::gpu

namespace sixway::runtime {
class SimulatedVolumes;
}

namespace sixway::eval {

class SceneEvaluation {
 public:
  // Opens the scene's smoke (a VDB scene's `grid` becomes its playback lattice) and makes every renderer.
  SceneEvaluation(const gpu::Context& context, const gpu::PipelineCache& cache,
                  const SceneEvalSettings& settings, scene::Scene scene);
  ~SceneEvaluation();

  // Prints what is evaluated, evaluates every frame (a line each) and writes the report, whose summary it
  // prints.
  void run();

 private:
  // The frame being evaluated: where it is in the sequence, its smoke and view, and its report entry.
  struct Frame {
    int i = 0;      // evaluated frame
    int index = 0;  // scene frame: the warm-up frames + i
    double seconds = 0;
    render::Volume volume;
    render::Camera camera;
    nlohmann::json json;
  };
  using Mask = std::vector<uint8_t>;
  using Rendered = std::map<std::string, modes::RenderedFrame>;

  void printHeading() const;
  void evaluateFrame(int i);
  Frame beginFrame(int i);
  modes::RenderedFrame traceTruth(Frame& frame);
  // With --truth-noise: the truth traced again with other noise, and the mask of its smoke where the images'
  // detail is measured.
  std::optional<Mask> measureTruthNoise(Frame& frame, const io::Image& truth);
  // The band around the obstacles (obstacle_band.h), where the images draw them.
  std::optional<Mask> obstacleBandOf(Frame& frame);
  modes::RenderedFrame renderMethod(const std::string& method, Frame& frame, const io::Image& truth,
                                    const Mask* band, const Mask* detailMask);
  void measureLightmaps(Frame& frame);
  void writeStrip(const Frame& frame, const io::Image& truth, const Rendered& rendered);
  void studyEqualTime(const Frame& frame, const Rendered& rendered);
  void endFrame(Frame& frame, const io::Image& truth, Rendered& rendered);
  void printProgress(const Frame& frame) const;
  nlohmann::json summary();
  nlohmann::json report(const nlohmann::json& summary) const;

  const SceneEvalSettings& s_;
  const std::vector<std::string> methodNames_;  // measured against the truth, in report order
  const gpu::Context& context_;
  const gpu::PipelineCache& cache_;
  scene::Scene scene_;
  // The scene's warm-up frames (render.warmup_frames) are simulated but not evaluated, as `sixway render`
  // skips them: evaluated frame i is scene frame warmup + i (its smoke, camera and lights).
  const int warmup_;
  const int stripFrame_;
  const std::unique_ptr<render::VolumeSequence> volumes_;
  const runtime::SimulatedVolumes* simulated_;  // none for a played-back VDB scene
  // What the renderers see: the obstacles, unless left out (--no-obstacles).
  scene::Scene renderScene_;
  std::map<std::string, std::unique_ptr<modes::ModeRenderer>> methods_;
  std::unique_ptr<modes::ModeRenderer> truth_;
  std::unique_ptr<modes::ModeRenderer> truthNoise_;  // the same frames with other noise
  std::unique_ptr<render::ObstacleBvh> bandObstacles_;
  const render::Camera firstCamera_;  // where the traditional flipbook was baked

  // Summed or collected over the frames, for the summary.
  LightmapMetrics lightmapTotal_, lightmapMsTotal_;
  std::map<std::string, metrics::ImageError> imageTotal_;
  std::map<std::string, std::vector<double>> framePsnrs_;
  std::map<std::string, std::vector<nlohmann::json>> frameStages_;
  std::map<std::string, std::vector<double>>
      wallTimes_;  // per method, per frame: render() on the host's clock
  std::map<std::string, TemporalChange> temporal_;
  TemporalChange truthTemporal_;
  std::optional<TemporalChange> truthNoiseTemporal_;
  // High-pass energies summed over the frames (image_detail.h): each method's, and the truth's without its
  // noise.
  std::map<std::string, double> detailEnergy_;
  double truthDetailEnergy_ = 0;
  std::map<std::string, uint64_t> faultTotals_;  // pixels no renderer should make (metrics::imageFaults)

  nlohmann::json frames_ = nlohmann::json::array(), equalTime_, strip_;
  std::map<std::string, io::Image> previous_;  // the last frame of every method, "truth" included
  std::chrono::steady_clock::time_point started_;
};

}  // namespace sixway::eval
