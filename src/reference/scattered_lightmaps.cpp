#include "reference/scattered_lightmaps.h"

#include <algorithm>
#include <cmath>

#include "io/error.h"
#include "render/sixway.h"

namespace sixway::reference {
namespace {

constexpr int kAlpha = 6, kEmissive = 7;
constexpr float kEmptyAlpha = 1e-6f;  // below it a pixel holds no smoke to scatter light

void checkMultiple(const MultipleScattering& m, const BakeSettings& settings) {
  auto fail = [](const std::string& problem) { throw io::InputError("multiple scattering", problem); };
  if (m.samples < 1 || m.samples > (1u << 20)) fail("samples per pixel must be in 1..1048576");
  if (m.maxOrders < 2) fail("needs at least 2 scattering orders");
  if (m.downsample != 1 && m.downsample != 2 && m.downsample != 4 && m.downsample != 8)
    fail("downsample must be 1, 2, 4 or 8");
  if (!m.traceAllOrders && (settings.width % m.downsample != 0 || settings.height % m.downsample != 0))
    fail("the lightmap size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
         " is not a multiple of the downsample " + std::to_string(m.downsample));
}

// Bilinear weights of full-resolution pixel `x` on the low-resolution axis of `lowSize` pixels, `d` times
// coarser: pixel centres (x + 0.5) / d − 0.5, edges clamped.
struct Tap {
  int i0, i1;
  float t;
};
Tap tap(int x, int d, int lowSize) {
  const float u = std::clamp((float(x) + 0.5f) / float(d) - 0.5f, 0.0f, float(lowSize - 1));
  const int i0 = std::min(int(u), lowSize - 1);
  return {i0, std::min(i0 + 1, lowSize - 1), u - float(i0)};
}

}  // namespace

io::Image upsampleAlphaGuided(const io::Image& low, const io::Image& full) {
  const int w = full.width, h = full.height, lw = low.width, lh = low.height;
  const int d = lw > 0 ? w / lw : 0;
  if (low.channels.size() != size_t(render::kSixWayChannels) ||
      full.channels.size() != size_t(render::kSixWayChannels) || d < 1 || lw * d != w || lh * d != h)
    throw std::invalid_argument(
        "upsampleAlphaGuided: eight-channel images, the full size a multiple of the low");
  io::Image out(w, h, full.channels);
  auto at = [&](int x, int y, int c) {
    return low.pixels[(size_t(y) * lw + x) * render::kSixWayChannels + c];
  };
  for (int y = 0; y < h; ++y) {
    const Tap ty = tap(y, d, lh);
    for (int x = 0; x < w; ++x) {
      const Tap tx = tap(x, d, lw);
      auto up = [&](int c) {
        const float top = (1.0f - tx.t) * at(tx.i0, ty.i0, c) + tx.t * at(tx.i1, ty.i0, c);
        const float bottom = (1.0f - tx.t) * at(tx.i0, ty.i1, c) + tx.t * at(tx.i1, ty.i1, c);
        return (1.0f - ty.t) * top + ty.t * bottom;
      };
      const size_t p = (size_t(y) * w + x) * render::kSixWayChannels;
      const float alphaLow = up(kAlpha), alphaFull = full.pixels[p + kAlpha];
      if (alphaLow <= kEmptyAlpha) continue;
      for (int c = 0; c < render::kSixWayLights; ++c) out.pixels[p + c] = alphaFull * up(c) / alphaLow;
      out.pixels[p + kEmissive] = alphaFull * up(kEmissive) / alphaLow;
    }
  }
  return out;
}

ScatteredLightmaps::ScatteredLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache)
    : context_(&context), cache_(&cache), baker_(context, cache) {}

ScatteredLightmaps::~ScatteredLightmaps() = default;

double ScatteredLightmaps::milliseconds() const {
  double total = 0.0;
  for (const gpu::StageTime& t : stages_) total += t.milliseconds;
  return total;
}

io::Image ScatteredLightmaps::bake(const render::Volume& volume, const scene::Smoke& smoke,
                                   const render::Camera& camera, const render::ImagePlane& billboard,
                                   const BakeSettings& settings, Scattering scattering,
                                   const MultipleScattering& multiple) {
  if (scattering == Scattering::Multiple) checkMultiple(multiple, settings);
  io::Image lightmaps = baker_.bake(volume, smoke, camera, billboard, settings);
  stages_ = baker_.stageTimes();
  single_ = multiple.traceAllOrders && scattering == Scattering::Multiple ? io::Image() : lightmaps;
  if (scattering == Scattering::Single) return lightmaps;

  if (!tracer_) tracer_ = std::make_unique<PathTracer>(*context_, *cache_);
  TraceSettings trace;
  trace.maxOrders = multiple.maxOrders;
  trace.seed = multiple.seed;
  trace.sixWayLights = settings.lights;
  if (multiple.traceAllOrders) {
    trace.width = settings.width;
    trace.height = settings.height;
    trace.jitter = false;  // pixel centres, as the exact baker samples
  } else {
    trace.width = settings.width / multiple.downsample;
    trace.height = settings.height / multiple.downsample;
    trace.minOrder = 2;  // the baker has the first order exactly
    // Downsampled, each traced pixel is the mean over its footprint, which the upsampling assumes; at full
    // resolution, pixel centres, as the baker samples.
    trace.jitter = multiple.downsample > 1;
  }
  tracer_->beginSixWay(volume, smoke, camera, billboard, trace);
  tracer_->accumulate(multiple.samples);
  stages_.push_back({"path trace", tracer_->traceMilliseconds()});
  const io::Image traced = tracer_->image();

  if (multiple.traceAllOrders) {
    for (size_t p = 0; p < size_t(settings.width) * settings.height; ++p)
      for (int c : {0, 1, 2, 3, 4, 5, kEmissive})
        lightmaps.pixels[p * render::kSixWayChannels + c] = traced.pixels[p * render::kSixWayChannels + c];
    return lightmaps;
  }
  const io::Image higher = upsampleAlphaGuided(traced, lightmaps);
  for (size_t i = 0; i < lightmaps.pixels.size(); ++i) lightmaps.pixels[i] += higher.pixels[i];
  return lightmaps;
}

}  // namespace sixway::reference
