#pragma once
// What a sixway::SmokeSimulation holds: its scene and the simulated volumes on the device.
#include <sixway/smoke_simulation.h>

#include <glm/mat4x4.hpp>
#include <memory>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/obj.h"
#include "runtime/scene_volumes.h"
#include "scene/scene.h"

namespace sixway {

struct SmokeSimulation::Impl {
  Impl(const gpu::Context& context, const gpu::PipelineCache& cache, scene::Scene scene);
  // A fresh simulation of the scene (the previous one's memory freed first).
  void start();

  const gpu::Context& context;
  const gpu::PipelineCache& cache;
  scene::Scene scene;
  std::unique_ptr<runtime::SimulatedVolumes> volumes;
  int frames = 0;         // frames simulated (or recorded) since the start
  uint64_t starts = 0;    // how often the simulation was started: a renderer re-records after a restart
  bool advanced = false;  // stage times exist
  double carried = 0.0;   // frame time not yet simulated (s), less than a step
  uint32_t maxStepsPerRecord = 0;
  glm::mat4 placement{1.0f};  // world from scene
  // The last setObstacles (a mesh's triangles in `mesh`, its spans empty), until a restart.
  struct EngineObstacle {
    Obstacle obstacle;
    std::shared_ptr<const io::Mesh> mesh;
  };
  std::vector<EngineObstacle> engineObstacles;
  glm::mat4 obstaclesPlacement{1.0f};  // the placement they were given in (another turns them: new shapes)
};

}  // namespace sixway
