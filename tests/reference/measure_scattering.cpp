// The numbers of docs/reference-rendering.md, "Fast multiple-scattering lightmaps": the split (exact single
// scattering + orders ≥ 2 path-traced at 1/d resolution) against every order path-traced at full resolution
// with many samples, for several d and sample counts: masked PSNR per light channel, pooled PSNR, and GPU
// time. The volume: tests/data/vdb/densityAndHeat.vdb resampled onto a cube of `cells`³ cubic cells.
// Usage: reference_scattering [lightmap size = 64] [cells = 64] [truth spp = 4096]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "reference/scattered_lightmaps.h"
#include "render/billboard.h"
#include "render/sixway.h"
#include "vdb_cube.h"

namespace {

using namespace sixway;

constexpr float kMaskAlpha = 0.01f;  // the metrics' mask (docs/conventions.md, "Metrics")

// Masked PSNR (peak 1) of each light channel of `image` against `truth`, then all six pooled.
std::vector<double> maskedPsnr(const io::Image& image, const io::Image& truth) {
  std::vector<double> sum(render::kSixWayLights + 1, 0.0);
  size_t count = 0;
  for (size_t p = 0; p < size_t(truth.width) * truth.height; ++p) {
    if (truth.pixels[p * 8 + 6] <= kMaskAlpha) continue;
    ++count;
    for (int c = 0; c < render::kSixWayLights; ++c) {
      const double e = double(image.pixels[p * 8 + c]) - truth.pixels[p * 8 + c];
      sum[c] += e * e;
      sum.back() += e * e / render::kSixWayLights;
    }
  }
  std::vector<double> psnr;
  for (double s : sum) psnr.push_back(10.0 * std::log10(1.0 / std::max(s / double(count), 1e-20)));
  return psnr;
}

// `traceMs` over `samples` traced paths: the tracer's cost per sample.
void printRow(const std::string& method, const std::vector<double>& psnr, double ms, double traceMs,
              double samples) {
  std::printf("| %s |", method.c_str());
  for (double v : psnr) std::printf(" %.2f |", v);
  std::printf(" %.0f | %s |\n", ms, samples > 0 ? std::to_string(int(traceMs * 1e6 / samples)).c_str() : "–");
}

double traceMilliseconds(const reference::ScatteredLightmaps& lightmaps) {
  for (const gpu::StageTime& t : lightmaps.stageTimes())
    if (t.name == "path trace") return t.milliseconds;
  return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  const int size = argc > 1 ? std::atoi(argv[1]) : 64;
  const int cells = argc > 2 ? std::atoi(argv[2]) : 64;
  const uint32_t truthSpp = argc > 3 ? uint32_t(std::atoi(argv[3])) : 4096u;
  gpu::Context context{gpu::ContextOptions{}};
  gpu::PipelineCache cache(context, gpu::defaultPipelineCacheFile(context));
  std::printf("device: %s; lightmaps %d², volume %d³, truth %u spp\n", context.properties().deviceName, size,
              cells, truthSpp);

  const render::DeviceVolume volume = render::uploadVolume(context, test::densityAndHeatCube(cells));
  scene::Smoke smoke;  // 0.3 optical depth per cell of a 128³ lattice at the densest cells, albedo 0.9
  smoke.extinction = 0.3f / (volume.grid().cellSize * float(cells) / 128.0f);
  const render::Box box = volume.grid().bounds();
  const render::Camera camera = render::Camera::lookAt(
      box.centre() + glm::length(box.size()) * glm::vec3(0.9f, 0.6f, 1.2f), box.centre(), {0, 1, 0}, 40.0f);
  const render::ImagePlane billboard = render::billboardBounds(camera, box, 1.0f);
  reference::BakeSettings settings;
  settings.width = settings.height = size;

  reference::ScatteredLightmaps lightmaps(context, cache);
  auto bake = [&](reference::Scattering scattering, const reference::MultipleScattering& m) {
    return lightmaps.bake(volume.view(), smoke, camera, billboard, settings, scattering, m);
  };
  reference::MultipleScattering reference;
  reference.traceAllOrders = true;
  reference.samples = truthSpp;
  const io::Image truth = bake(reference::Scattering::Multiple, reference);
  const double truthMs = lightmaps.milliseconds();
  std::printf("\n| method | right | left | top | bottom | back | front | all six | GPU ms | ns/sample |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  printRow("all orders traced, " + std::to_string(truthSpp) + " spp (truth)",
           std::vector<double>(7, INFINITY), truthMs, traceMilliseconds(lightmaps),
           double(size) * size * truthSpp);
  reference.seed = 2;
  reference.samples = truthSpp / 16;
  const io::Image lessSamples = bake(reference::Scattering::Multiple, reference);
  printRow("all orders traced, " + std::to_string(truthSpp / 16) + " spp", maskedPsnr(lessSamples, truth),
           lightmaps.milliseconds(), traceMilliseconds(lightmaps), double(size) * size * reference.samples);
  const io::Image single = bake(reference::Scattering::Single, {});
  printRow("single scattering (exact baker)", maskedPsnr(single, truth), lightmaps.milliseconds(), 0, 0);
  for (int d : {1, 2, 4})
    for (uint32_t spp : {16u, 64u, 256u}) {
      reference::MultipleScattering split;
      split.downsample = d;
      split.samples = spp;
      split.seed = 3;
      const io::Image image = bake(reference::Scattering::Multiple, split);
      printRow("split, 1/" + std::to_string(d) + ", " + std::to_string(spp) + " spp",
               maskedPsnr(image, truth), lightmaps.milliseconds(), traceMilliseconds(lightmaps),
               double(size / d) * (size / d) * spp);
    }
  return 0;
}
