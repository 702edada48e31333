#include "eval/lightmap_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/sixway.h"

namespace sixway::eval {
namespace {

using render::SixWayChannel;

// The channel pair of each channel: right/left, top/bottom, back/front, alpha/emissive.
constexpr std::array<int, render::kSixWayChannels> kPairOf{0, 0, 1, 1, 2, 2, 3, 3};

float clipped(float v) {
  return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
}

}  // namespace

double LightmapMetrics::Sum::psnr() const {
  if (values == 0) return std::numeric_limits<double>::quiet_NaN();
  const double mse = squared / double(values);
  return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

void LightmapMetrics::add(std::span<const float> predicted, std::span<const float> reference) {
  constexpr int kChannels = render::kSixWayChannels;
  if (predicted.size() != reference.size() || predicted.size() % kChannels != 0)
    throw std::invalid_argument("LightmapMetrics::add: the images differ in size");
  Sum sample;
  for (size_t p = 0; p < predicted.size(); p += kChannels) {
    const bool inside = reference[p + SixWayChannel::Alpha] > 0.01f;
    for (int c = 0; c < kChannels; ++c) {
      const double d = double(clipped(predicted[p + c])) - double(clipped(reference[p + c]));
      full_.squared += d * d;
      ++full_.values;
      if (!inside) continue;
      sample.squared += d * d;
      ++sample.values;
      pairs_[kPairOf[c]].squared += d * d;
      ++pairs_[kPairOf[c]].values;
      channels_[c].squared += d * d;
      ++channels_[c].values;
    }
  }
  masked_.squared += sample.squared;
  masked_.values += sample.values;
  if (sample.values > 0) {
    samplePsnrSum_ += std::min(sample.psnr(), 100.0);  // an exact sample counts as 100 dB
    ++maskedSamples_;
  }
  ++samples_;
}

nlohmann::json LightmapMetrics::summary() const {
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json channels = nlohmann::json::object();
  for (int c = 0; c < render::kSixWayChannels; ++c)
    channels[render::sixWayChannelNames()[c]] = number(channels_[c].psnr());
  return {
      {"samples", samples_},
      {"psnr_masked_db", number(masked_.psnr())},
      {"psnr_full_db", number(full_.psnr())},
      {"mean_sample_psnr_masked_db", number(maskedSamples_ ? samplePsnrSum_ / double(maskedSamples_) : NAN)},
      {"pairs_psnr_masked_db",
       {{"right_left", number(pairs_[0].psnr())},
        {"top_bottom", number(pairs_[1].psnr())},
        {"back_front", number(pairs_[2].psnr())},
        {"alpha_emissive", number(pairs_[3].psnr())}}},
      {"channels_psnr_masked_db", channels}};
}

}  // namespace sixway::eval
