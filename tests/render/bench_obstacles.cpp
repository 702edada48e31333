// The timings of docs/real-time-rendering.md, "Obstacles and shadows" (not a test): GPU time of the stages
// "shadow maps" and "obstacles" for each scene given, at 256² and 512², shadow tiles of TILE² (default 1024).
// Frames advance (moving obstacles and orbiting lights are placed anew each frame, the sequence is recorded
// once); the time is the median of 20 frames after 3 warm-up frames, from GPU timestamps. "with smoke" times
// the obstacles again with the scene's grid filled with smoke of density 1 (every light and the ambient
// marched through the whole domain: the most the pass's smoke lighting costs). Usage: obstacle_bench [--tile
// TILE] SCENE.json...
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/image.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "render/obstacle_meshes.h"
#include "render/obstacle_pass.h"
#include "render/projection.h"
#include "render/scene_frame.h"
#include "render/shadow_maps.h"
#include "render/volume.h"

namespace {

using namespace sixway;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int first = 1;
  uint32_t tileSize = render::kDefaultShadowTileSize;
  if (argc > 2 && std::string(argv[1]) == "--tile") tileSize = uint32_t(std::stoul(argv[2])), first = 3;
  if (first >= argc) {
    std::fprintf(stderr, "usage: obstacle_bench [--tile TILE] SCENE.json...\n");
    return 2;
  }
  gpu::Context context;
  gpu::PipelineCache cache(context);
  std::printf("device: %s (%s)\n", context.properties().deviceName, context.driver().driverInfo);
  std::printf("shadow tiles of %ux%u\n", tileSize, tileSize);
  std::printf("%-20s %10s %6s %5s %18s %14s %14s\n", "scene", "triangles", "size", "tiles", "shadow maps ms",
              "obstacles ms", "with smoke ms");
  for (int a = first; a < argc; ++a) {
    const scene::Scene scene = scene::loadScene(argv[a]);
    render::ObstacleMeshes meshes(context, scene.obstacles);
    const uint32_t tiles = render::shadowTileCount(scene.lights, scene.obstacles);
    render::ShadowMaps shadows(context, cache, tileSize, tiles);
    render::ObstaclePass pass(context, cache, scene.render.background);
    const render::VolumeGrid grid{scene.grid.size, scene.grid.origin, scene.grid.cellSize};
    render::DeviceVolume smoke(context, grid, false);
    smoke.upload(std::vector<float>(grid.cellCount(), 1.0f));
    const render::Volume smokeView = smoke.view();
    for (uint32_t size : {256u, 512u}) {
      gpu::Image color(context, {size, size, 1, render::ObstaclePass::kColorFormat,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "colour"});
      gpu::Image depth(context, {size, size, 1, render::ObstaclePass::kDepthFormat,
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth"});
      gpu::Sequence sequence(context), smoky(context);
      shadows.record(sequence, meshes);
      pass.record(sequence, meshes, shadows, color, depth);
      sequence.finish();
      pass.record(smoky, meshes, shadows, color, depth, &smokeView, scene.smoke);
      smoky.finish();
      std::map<std::string, std::vector<double>> times;
      for (int frame = 0; frame < 23; ++frame) {
        meshes.update(frame * double(scene.time.frameDt));
        const render::Camera camera = render::sceneCamera(scene.camera, frame);
        const std::vector<scene::Light> lights = render::sceneLights(scene.lights, frame);
        const render::Box bounds = render::sceneBounds(render::domainBox(scene.grid), meshes);
        shadows.update(lights, bounds, meshes);
        pass.update(camera, render::fullFrame(camera, int(size), int(size)),
                    render::boxDepthRange(camera, bounds), lights, scene.ambient, shadows);
        sequence.submit();
        for (const std::string& note : shadows.takeNotes())
          std::printf("  note (frame %d): %s\n", frame, note.c_str());
        smoky.submit();
        if (frame >= 3) {
          for (const gpu::StageTime& t : sequence.stageTimes()) times[t.name].push_back(t.milliseconds);
          for (const gpu::StageTime& t : smoky.stageTimes())
            times["smoky " + t.name].push_back(t.milliseconds);
        }
      }
      std::printf("%-20s %10u %6u %5u %18.2f %14.2f %14.2f\n", scene.name.c_str(), meshes.indexCount() / 3,
                  size, tiles, median(times["shadow maps"]), median(times["obstacles"]),
                  median(times["smoky obstacles"]));
    }
  }
}
