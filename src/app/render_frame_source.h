#pragma once
// Where the frames of `sixway render` (render_command.h) come from, all from the runtime's one real-time
// frame: the scene's smoke, simulated or played back from its VDB files, and the mode's renderer. neural on a
// simulation goes through the public SmokeRenderer (the product's path, as an engine runs it); the
// evaluation's modes through modes::ModeRenderer on the same simulation. A VDB scene has no simulation for
// the public API to run: every mode, neural included, goes through ModeRenderer on the played-back volumes.
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>
#include <filesystem>
#include <memory>
#include <optional>

#include "modes/mode_renderer.h"
#include "render/volume_sequence.h"
#include "scene/scene.h"

namespace sixway::app {

class RenderFrameSource {
 public:
  // The smoke of `frames` frames (a VDB scene's `grid` becomes its playback lattice) and the mode's renderer.
  // What the device cannot hold is an error that names the scene and the setting to reduce.
  RenderFrameSource(sixway::Device& device, scene::Scene& scene, const std::filesystem::path& scenePath,
                    int frames, const modes::ModeOptions& options);
  ~RenderFrameSource();

  // Simulates the warm-up frames, a line each; played-back smoke needs none.
  void warmUp(int frames);
  // Frame `index` (the simulation advanced to it): its image, GPU stage times (the simulation's first) and
  // notes.
  modes::RenderedFrame render(int index);
  // The played-back VDB sequence; none for a simulated scene.
  const render::VolumeSequence* playback() const { return playback_.get(); }

 private:
  void openSmoke(const std::filesystem::path& scenePath, int frames);
  void makeRenderer(const std::filesystem::path& scenePath, const modes::ModeOptions& options);
  modes::RenderedFrame renderNeural();

  sixway::Device& device_;
  scene::Scene& scene_;
  std::optional<sixway::SmokeSimulation> simulation_;
  std::unique_ptr<render::VolumeSequence> playback_;
  std::unique_ptr<sixway::SmokeRenderer> renderer_;
  std::unique_ptr<modes::ModeRenderer> modeRenderer_;
};

}  // namespace sixway::app
