// The figures and numbers of docs/reference-rendering.md: one frame of a real OpenVDB sequence
// (tests/data/vdb/smoke_000003.vdb, Blender smoke) baked by the exact baker, path-traced as six-way lightmaps
// (single and multiple scattering), and path-traced under a directional light beside the six-way shading of
// its lightmaps (docs/conventions.md, "Shading"). Writes PNGs (sRGB, premultiplied over black) into the
// directory given and prints the measured differences.
// Usage: reference_figures OUT_DIR
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "io/png.h"
#include "io/vdb.h"
#include "reference/lightmap_baker.h"
#include "reference/path_tracer.h"
#include "reference/vdb_sequence.h"
#include "render/billboard.h"
#include "render/sixway.h"

namespace {

using namespace sixway;

constexpr int kSize = 128;

// Channels of several images side by side, grey, 2-pixel white gaps; each panel scaled by `exposure` except
// alpha panels.
io::Image strip(const std::vector<std::pair<const io::Image*, int>>& panels, float exposure) {
  const int n = int(panels.size());
  io::Image out(n * kSize + (n - 1) * 2, kSize, {"R", "G", "B"});
  std::fill(out.pixels.begin(), out.pixels.end(), 1.0f);
  for (int i = 0; i < n; ++i)
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int k = 0; k < 3; ++k) {
          const auto [image, c] = panels[i];
          const bool alpha = image->channels[c] == "alpha";
          out.at(i * (kSize + 2) + x, y, k) = (alpha ? 1.0f : exposure) * image->at(x, y, c);
        }
  return out;
}

// RMS difference of channel a of image A and channel b of image B, and PSNR per docs/conventions.md,
// "Metrics" (values clipped to [0, 1]) over the pixels where the reference alpha exceeds 0.01.
struct Difference {
  double rms, maskedPsnr;
};
Difference difference(const io::Image& A, int a, const io::Image& B, int b, const io::Image& alpha) {
  double sum = 0, masked = 0;
  int count = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double d = double(A.at(x, y, a)) - B.at(x, y, b);
      sum += d * d;
      if (alpha.at(x, y, render::Alpha) > 0.01f) {
        const double c =
            std::clamp(double(A.at(x, y, a)), 0.0, 1.0) - std::clamp(double(B.at(x, y, b)), 0.0, 1.0);
        masked += c * c;
        ++count;
      }
    }
  return {std::sqrt(sum / (kSize * kSize)), 10 * std::log10(count / masked)};
}

// Six-way shading (docs/conventions.md, "Shading") of lightmaps under one white directional light of
// irradiance π: the light direction d in the billboard frame picks A or B per axis, t = Σ d_i² w_i.
io::Image shade(const io::Image& lightmaps, const render::Camera& camera, glm::vec3 toLight) {
  const glm::vec3 d(glm::dot(toLight, camera.right), glm::dot(toLight, camera.up),
                    glm::dot(toLight, camera.forward));
  io::Image out(kSize, kSize, {"Y"});
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float wx = lightmaps.at(x, y, d.x >= 0 ? render::Right : render::Left);
      const float wy = lightmaps.at(x, y, d.y >= 0 ? render::Top : render::Bottom);
      const float wz = lightmaps.at(x, y, d.z >= 0 ? render::Back : render::Front);
      out.at(x, y, 0) = d.x * d.x * wx + d.y * d.y * wy + d.z * d.z * wz;
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: reference_figures OUT_DIR\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  gpu::Context context;
  gpu::PipelineCache cache(context);
  reference::VdbSequence sequence(context, {SIXWAY_TEST_DATA_DIR "/vdb/smoke_000003.vdb"}, 96, false);
  const render::Volume volume = *sequence.frame(0);
  const render::Box box = sequence.bounds();
  // Blender is z-up: look at the column of smoke from the side, z up.
  const render::Camera camera = render::Camera::lookAt(
      box.centre() + glm::vec3(0.0f, -2.2f * glm::length(box.size()), 0.0f), box.centre(), {0, 0, 1}, 40.0f);
  const render::ImagePlane billboard = render::billboardBounds(camera, box, 1.0f);
  scene::Smoke smoke;
  smoke.extinction = 3.0f;  // per unit of the file's world units; ≈ 0.4 optical depth per cell at density 1
  smoke.albedo = 0.9f;
  smoke.phaseG = 0.3f;
  std::printf("lattice %dx%dx%d, cell %.4f\n", volume.grid.size.x, volume.grid.size.y, volume.grid.size.z,
              volume.grid.cellSize);

  reference::LightmapBaker baker(context, cache);
  reference::BakeSettings bake;
  bake.width = bake.height = kSize;
  const io::Image baked = baker.bake(volume, smoke, camera, billboard, bake);
  double bakeMs = 0;
  for (const auto& t : baker.stageTimes()) bakeMs += t.milliseconds;

  reference::PathTracer tracer(context, cache);
  reference::TraceSettings trace;
  trace.width = trace.height = kSize;
  trace.jitter = false;
  trace.samplesPerPass = 16;
  trace.maxOrders = 1;
  tracer.beginSixWay(volume, smoke, camera, billboard, trace);
  tracer.accumulate(1024);
  const io::Image single = tracer.image();
  trace.maxOrders = 64;
  tracer.beginSixWay(volume, smoke, camera, billboard, trace);
  tracer.accumulate(1024);
  const io::Image multiple = tracer.image();

  std::printf(
      "baker %.0f ms GPU\n| channel | baker peak | path tracer (1 order, 1024 spp) RMS diff | masked PSNR | "
      "multiple / single scattering (mean) |\n|---|---|---|---|---|\n",
      bakeMs);
  for (int c = 0; c <= render::Alpha; ++c) {  // this file has no temperature: no emission
    double peak = 0, sumSingle = 0, sumMultiple = 0;
    for (int i = 0; i < kSize * kSize; ++i) {
      peak = std::max(peak, double(baked.pixels[i * 8 + c]));
      sumSingle += single.pixels[i * 8 + c];
      sumMultiple += multiple.pixels[i * 8 + c];
    }
    const Difference d = difference(single, c, baked, c, baked);
    std::printf("| %s | %.3f | %.4f | %.1f dB | %.2f |\n", baked.channels[c].c_str(), peak, d.rms,
                d.maskedPsnr, sumMultiple / sumSingle);
  }
  const std::vector<int> six = {render::Right,  render::Left, render::Top,
                                render::Bottom, render::Back, render::Front};
  auto row = [&](const io::Image& image) {
    std::vector<std::pair<const io::Image*, int>> panels;
    for (int c : six) panels.push_back({&image, c});
    panels.push_back({&image, render::Alpha});
    return panels;
  };
  io::writePng(out / "reference-lightmaps-baker.png", strip(row(baked), 4.0f));
  io::writePng(out / "reference-lightmaps-pathtraced.png", strip(row(single), 4.0f));
  io::writePng(out / "reference-lightmaps-multiple.png", strip(row(multiple), 1.0f));

  // A final image under one light from upper right, in front: path-traced (single and multiple scattering),
  // and six-way shading of the matching lightmaps.
  const glm::vec3 toLight = glm::normalize(0.6f * camera.right + 0.5f * camera.up - 0.6f * camera.forward);
  const scene::Light sun{scene::DirectionalLight{toLight}, glm::vec3(1.0f), std::numbers::pi_v<float>};
  trace.maxOrders = 1;
  tracer.beginImage(volume, smoke, camera, billboard, {sun}, trace);
  tracer.accumulate(1024);
  const io::Image tracedSingle = tracer.image();
  trace.maxOrders = 64;
  tracer.beginImage(volume, smoke, camera, billboard, {sun}, trace);
  tracer.accumulate(1024);
  const io::Image tracedMultiple = tracer.image();
  const io::Image shadedSingle = shade(baked, camera, toLight),
                  shadedMultiple = shade(multiple, camera, toLight);
  io::Image diffSingle = shadedSingle, diffMultiple = shadedMultiple;
  for (int i = 0; i < kSize * kSize; ++i) {
    diffSingle.pixels[i] = std::fabs(shadedSingle.pixels[i] - tracedSingle.pixels[i * 4]);
    diffMultiple.pixels[i] = std::fabs(shadedMultiple.pixels[i] - tracedMultiple.pixels[i * 4]);
  }
  io::writePng(out / "reference-light-single.png",
               strip({{&tracedSingle, 0}, {&shadedSingle, 0}, {&diffSingle, 0}}, 4.0f));
  io::writePng(out / "reference-light-multiple.png",
               strip({{&tracedMultiple, 0}, {&shadedMultiple, 0}, {&diffMultiple, 0}}, 1.0f));
  const Difference s = difference(shadedSingle, 0, tracedSingle, 0, baked);
  const Difference m = difference(shadedMultiple, 0, tracedMultiple, 0, baked);
  std::printf(
      "six-way shading vs path tracing under one light: single scattering RMS %.4f, masked PSNR %.1f dB; "
      "multiple scattering RMS %.4f, masked PSNR %.1f dB\n",
      s.rms, s.maskedPsnr, m.rms, m.maskedPsnr);
  return 0;
}
