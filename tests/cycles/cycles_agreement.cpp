#include "cycles/cycles_agreement.h"

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

// One renderer's values of a channel: the mean of its renders, and their noise variance (the mean's) summed
// over the mask.
struct Side {
  std::vector<float> mean;
  double noise = 0;
};

Side sideOf(const std::vector<const std::vector<float>*>& renders, const std::vector<bool>& mask) {
  if (renders.empty() || renders.size() > 2) throw std::invalid_argument("one or two renders per side");
  Side side{*renders.front(), 0};
  if (renders.size() == 2)
    for (std::size_t i = 0; i < mask.size(); ++i) {
      const float a = (*renders[0])[i], b = (*renders[1])[i];
      side.mean[i] = 0.5f * (a + b);
      if (mask[i]) {
        const double d = double(clipped(a)) - clipped(b);
        side.noise += d * d / 4;
      }
    }
  return side;
}

void add(Agreement& group, const std::vector<const std::vector<float>*>& tested,
         const std::vector<const std::vector<float>*>& reference, const std::vector<bool>& mask) {
  const Side a = sideOf(tested, mask), b = sideOf(reference, mask);
  double squared = 0, testedSum = 0, referenceSum = 0;
  std::size_t values = 0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) {
      const double t = clipped(a.mean[i]), r = clipped(b.mean[i]);
      squared += (t - r) * (t - r);
      testedSum += t;
      referenceSum += r;
      ++values;
    }
  const double total = double(group.values + values);
  if (total == 0) return;
  // Pooled as sums, then back to means.
  group.mse = (group.mse * group.values + squared) / total;
  group.noiseMse = (group.noiseMse * group.values + a.noise + b.noise) / total;
  group.testedMean = (group.testedMean * group.values + testedSum) / total;
  group.referenceMean = (group.referenceMean * group.values + referenceSum) / total;
  group.values += values;
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

double Agreement::psnrDb() const {
  return psnr(mse);
}

double Agreement::noiseFloorDb() const {
  return psnr(noiseMse);
}

double Agreement::biasPsnrDb() const {
  return psnr(mse - noiseMse);
}

nlohmann::json Agreement::json() const {
  return {{"psnr_db", decibels(psnrDb())},
          {"noise_floor_db", decibels(noiseFloorDb())},
          {"noise_removed_psnr_db", decibels(biasPsnrDb())},
          {"values", values},
          {"tested_mean", testedMean},
          {"reference_mean", referenceMean}};
}

Agreement compareRenders(const std::vector<Render>& tested, const std::vector<Render>& reference,
                         const std::vector<int>& channels) {
  requireAlike(tested, reference);
  const std::vector<bool> mask = maskOf(reference);
  Agreement result;
  for (int c : channels) {
    std::vector<const std::vector<float>*> a, b;
    for (const Render& r : tested) a.push_back(&r.channels.at(c));
    for (const Render& r : reference) b.push_back(&r.channels.at(c));
    add(result, a, b, mask);
  }
  return result;
}

Agreement compareAlpha(const std::vector<Render>& tested, const std::vector<Render>& reference) {
  requireAlike(tested, reference);
  std::vector<const std::vector<float>*> a, b;
  for (const Render& r : tested) a.push_back(&r.alpha);
  for (const Render& r : reference) b.push_back(&r.alpha);
  Agreement result;
  add(result, a, b, maskOf(reference));
  return result;
}

double maskedFraction(const std::vector<Render>& reference) {
  const std::vector<bool> mask = maskOf(reference);
  return mask.empty() ? 0 : double(std::count(mask.begin(), mask.end(), true)) / double(mask.size());
}

}  // namespace sixway::test
