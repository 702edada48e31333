#include "runtime/network_lightmaps.h"

#include <stdexcept>
#include <string>

#include "runtime/network_weights.h"

namespace sixway::runtime {
namespace {

// Fp16 or fp32 feature maps, an emissive output only for smoke that glows, the smoke's albedo.
nn::NetworkOptions sceneNetworkOptions(const scene::Scene& scene, bool fp16) {
  nn::NetworkOptions options;
  options.precision = fp16 ? nn::Precision::Fp16 : nn::Precision::Fp32;
  options.emission = scene.smoke.emission.intensity > 0.0f;
  options.albedo = scene.smoke.albedo;
  return options;
}

}  // namespace

NetworkLightmaps::NetworkLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                                   const scene::Scene& scene, const io::SafetensorsFile& weights, bool fp16)
    : network_(loadNetwork(context, cache, weights, uint32_t(scene.render.lightmapSize),
                           sceneNetworkOptions(scene, fp16))),
      albedo_(scene.smoke.albedo),
      size_(uint32_t(scene.render.lightmapSize)),
      emission_(sceneNetworkOptions(scene, fp16).emission) {}

NetworkLightmaps::NetworkLightmaps(const scene::Scene& scene, const NetworkLightmaps& other)
    : network_(other.network_),
      albedo_(scene.smoke.albedo),
      size_(uint32_t(scene.render.lightmapSize)),
      emission_(sceneNetworkOptions(scene, false).emission) {
  if (size_ != other.size_)
    throw std::invalid_argument(
        "the network is shared between lightmaps of one size: " + std::to_string(size_) + " here, " +
        std::to_string(other.size_) + " in the renderer it comes from");
  if (emission_ != other.emission_)
    throw std::invalid_argument(
        "the network is shared between scenes that both emit or both do not (smoke.emission.intensity)");
}

render::ImagePlane NetworkLightmaps::update(RealtimeFrame&, const SourceFrame& current) {
  network_->setAlbedo(albedo_);
  return current.billboard;
}

render::GuideSettings NetworkLightmaps::guide(const scene::Scene& scene) const {
  render::GuideSettings guide = LightmapSource::guide(scene);
  const nn::Node& input = network_->graph().nodes.front();
  if (input.guideAlphaStepVoxels > 0.0f) guide.alphaStepCells = input.guideAlphaStepVoxels;
  guide.emission = input.guideChannels > nn::kGuideImageChannels;
  return guide;
}

void NetworkLightmaps::record(gpu::Sequence& s, RealtimeFrame& frame) {
  s.beginStage("network");
  network_->record(s, {frame.guide(), frame.guideEmission()}, frame.lightmaps().a, frame.lightmaps().b);
  s.endStage();
  if (packed_) packed_->record(s, frame.lightmaps());
}

void NetworkLightmaps::packLightmaps(const gpu::Context& context, const gpu::PipelineCache& cache,
                                     const render::ChannelPacking& packing) {
  if (packing.textures == render::unityPacking().textures)
    packed_.reset();
  else
    packed_ = std::make_unique<render::LightmapRepack>(context, cache, size_, packing);
}

}  // namespace sixway::runtime
