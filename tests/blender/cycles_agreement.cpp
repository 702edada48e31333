#include "blender/cycles_agreement.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "io/exr.h"

namespace sixway::test {
namespace {

namespace fs = std::filesystem;

const std::array<std::string, 6> kLights = {"Right", "Left", "Top", "Bottom", "Back", "Front"};

std::vector<float> plane(const io::Image& image, int channel) {
  const std::size_t texels = std::size_t(image.width) * image.height;
  std::vector<float> out(texels);
  for (std::size_t i = 0; i < texels; ++i) out[i] = image.pixels[i * image.channelCount() + channel];
  return out;
}

float clipped(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

// One renderer's values of a channel, each render clipped first: their mean, and per value the mean's noise
// variance estimated from the two renders (0 from one).
struct Side {
  std::vector<float> mean, noise;
};

Side sideOf(const std::vector<const std::vector<float>*>& renders) {
  if (renders.empty() || renders.size() > 2) throw std::invalid_argument("one or two renders per side");
  const std::size_t n = renders.front()->size();
  Side side{std::vector<float>(n), std::vector<float>(n, 0.0f)};
  for (std::size_t i = 0; i < n; ++i) {
    const float a = clipped((*renders.front())[i]), b = clipped((*renders.back())[i]);
    side.mean[i] = 0.5f * (a + b);
    side.noise[i] = (a - b) * (a - b) / 4;
  }
  return side;
}

// Adds one channel; `perTexel` sums each texel's d² − noise over the channels (the estimate of its squared
// bias), whose spread gives the standard error: a texel's channels share their paths, so they are not
// independent of one another, but texels are (pixel-centre or box-filtered rays, independent per pixel).
void add(Agreement& group, std::vector<double>& perTexel,
         const std::vector<const std::vector<float>*>& tested,
         const std::vector<const std::vector<float>*>& reference, const std::vector<bool>& mask) {
  const Side a = sideOf(tested), b = sideOf(reference);
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      const double d = double(a.mean[i]) - b.mean[i], noise = double(a.noise[i]) + b.noise[i];
      group.squared += d * d;
      group.noise += noise;
      perTexel[i] += d * d - noise;
      group.tested += a.mean[i];
      group.reference += b.mean[i];
      ++group.values;
    }
}

void finish(Agreement& group, const std::vector<double>& perTexel, const std::vector<bool>& mask) {
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      group.texelBiasSquares += perTexel[i] * perTexel[i];
      ++group.texels;
    }
}

std::vector<bool> maskOf(const std::vector<Render>& reference) {
  const std::size_t texels = reference.front().alpha.size();
  std::vector<bool> mask(texels);
  for (std::size_t i = 0; i < texels; ++i) {
    float alpha = 0;
    for (const Render& r : reference) alpha += r.alpha[i] / float(reference.size());
    mask[i] = alpha > 0.01f;
  }
  return mask;
}

void requireAlike(const std::vector<Render>& tested, const std::vector<Render>& reference) {
  if (reference.empty()) throw std::invalid_argument("no reference render");
  const Render& first = reference.front();
  for (const auto* side : {&tested, &reference})
    for (const Render& r : *side)
      if (r.width != first.width || r.height != first.height || r.channels.size() != first.channels.size() ||
          r.alpha.size() != first.alpha.size())
        throw std::invalid_argument("renders of different sizes or channels");
}

double psnr(double mse) {
  return mse <= 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(1 / mse);
}

nlohmann::json decibels(double db) {
  if (std::isnan(db)) return "nan";
  return std::isfinite(db) ? nlohmann::json(std::round(db * 100) / 100) : nlohmann::json("inf");
}

}  // namespace

Render readBakedFrame(const fs::path& exr) {
  std::vector<std::string> names(kLights.begin(), kLights.end());
  names.insert(names.end(), {"emissive", "alpha"});
  const io::Image image = io::readExr(exr, names).image;
  Render out{image.width, image.height, {}, plane(image, 7)};
  for (int c = 0; c < 7; ++c) out.channels.push_back(plane(image, c));
  return out;
}

Render readCyclesLightmaps(const fs::path& dir) {
  Render out;
  for (const std::string& light : kLights) {
    const io::Image image = io::readExr(dir / ("cycles_" + light + ".exr"), {"R", "A"}).image;
    if (out.channels.empty()) {
      out.width = image.width;
      out.height = image.height;
      out.alpha.assign(std::size_t(image.width) * image.height, 0.0f);
    }
    if (image.width != out.width || image.height != out.height)
      throw std::invalid_argument(dir.string() + ": the six renders differ in size");
    out.channels.push_back(plane(image, 0));
    const std::vector<float> alpha = plane(image, 1);
    for (std::size_t i = 0; i < alpha.size(); ++i) out.alpha[i] += alpha[i] / float(kLights.size());
  }
  const fs::path emissive = dir / "cycles_emissive.exr";
  out.channels.emplace_back(out.alpha.size(), 0.0f);
  if (fs::exists(emissive)) {
    const io::Image image = io::readExr(emissive, {"R"}).image;
    if (image.width != out.width || image.height != out.height)
      throw std::invalid_argument(emissive.string() + ": another size than the light renders");
    out.channels.back() = image.pixels;
  }
  return out;
}

Render readRenderedFrame(const fs::path& exr) {
  const io::Image image = io::readExr(exr, {"R", "G", "B", "A"}).image;
  return {image.width, image.height, {plane(image, 0), plane(image, 1), plane(image, 2)}, plane(image, 3)};
}

Render readCyclesImage(const fs::path& dir) {
  const io::Image image = io::readExr(dir / "cycles.exr", {"R", "G", "B", "A"}).image;
  std::ifstream in(dir / "cycles.json");
  const std::vector<float> background = nlohmann::json::parse(in).at("background").get<std::vector<float>>();
  Render out{image.width, image.height, {}, plane(image, 3)};
  for (int c = 0; c < 3; ++c) {
    out.channels.push_back(plane(image, c));
    for (std::size_t i = 0; i < out.alpha.size(); ++i)
      out.channels[c][i] += (1.0f - out.alpha[i]) * background.at(c);
  }
  return out;
}

// Nothing to compare is no figure (NaN), never a perfect one.
double Agreement::psnrDb() const {
  return values ? psnr(squared / double(values)) : std::nan("");
}

double Agreement::noiseFloorDb() const {
  return values ? psnr(noise / double(values)) : std::nan("");
}

double Agreement::biasPsnrDb() const {
  return values ? psnr((squared - noise) / double(values)) : std::nan("");
}

double Agreement::biasPsnrLowerDb() const {
  if (!values) return std::nan("");
  // The squared-bias estimate is the sum over texels of their terms, over the values.
  const double n = double(texels), texelMean = (squared - noise) / n;
  const double spread = std::max(0.0, texelBiasSquares / n - texelMean * texelMean);
  return psnr((squared - noise + 2 * std::sqrt(n * spread)) / double(values));
}

nlohmann::json Agreement::json() const {
  return {{"psnr_db", decibels(psnrDb())},
          {"noise_floor_db", decibels(noiseFloorDb())},
          {"noise_removed_psnr_db", decibels(biasPsnrDb())},
          {"noise_removed_psnr_lower_bound_db", decibels(biasPsnrLowerDb())},
          {"values", values},
          {"tested_mean", tested / double(values)},
          {"reference_mean", reference / double(values)}};
}

Agreement compareRenders(const std::vector<Render>& tested, const std::vector<Render>& reference,
                         const std::vector<int>& channels) {
  requireAlike(tested, reference);
  const std::vector<bool> mask = maskOf(reference);
  Agreement result;
  std::vector<double> perTexel(mask.size(), 0.0);
  for (int c : channels) {
    std::vector<const std::vector<float>*> a, b;
    for (const Render& r : tested) a.push_back(&r.channels.at(c));
    for (const Render& r : reference) b.push_back(&r.channels.at(c));
    add(result, perTexel, a, b, mask);
  }
  finish(result, perTexel, mask);
  return result;
}

Agreement compareAlpha(const std::vector<Render>& tested, const std::vector<Render>& reference) {
  requireAlike(tested, reference);
  std::vector<const std::vector<float>*> a, b;
  for (const Render& r : tested) a.push_back(&r.alpha);
  for (const Render& r : reference) b.push_back(&r.alpha);
  const std::vector<bool> mask = maskOf(reference);
  Agreement result;
  std::vector<double> perTexel(mask.size(), 0.0);
  add(result, perTexel, a, b, mask);
  finish(result, perTexel, mask);
  return result;
}

double maskedFraction(const std::vector<Render>& reference) {
  const std::vector<bool> mask = maskOf(reference);
  return mask.empty() ? 0 : double(std::count(mask.begin(), mask.end(), true)) / double(mask.size());
}

}  // namespace sixway::test
