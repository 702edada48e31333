#pragma once
// The band of a frame where the smoke meets the obstacles (docs/conventions.md, "Metrics"), for the band PSNR
// of `sixway eval --scene`: the pixels within `radius` of an obstacle's footprint on the screen (its
// silhouette, from both sides), and the pixels whose camera ray passes through visible smoke in an obstacle's
// shadow. Visible smoke: a point of the ray whose cell attenuates light by at least 1% (σ_t·ρ·cell ≥ 0.01),
// seen through an optical depth under 4.6 (1% transmittance) from the camera; in shadow: a shadow-casting
// obstacle lies between it and a shadow-casting light.
#include <cstdint>
#include <vector>

#include "render/camera.h"
#include "render/obstacle_bvh.h"
#include "render/volume.h"
#include "scene/scene.h"

namespace sixway::eval {

// The smoke's density on the host, as render::Volume holds it on the device.
struct HostDensity {
  render::VolumeGrid grid;
  std::vector<float> values;  // x fastest, then y, then z
};

struct BandSettings {
  int radius = 8;        // pixels around the footprint
  bool shadows = true;   // include the shadowed smoke (false: the obstacles cast none in the images)
  float extinction = 0;  // σ_t per unit density
};

// The footprint dilation for a frame of `height` pixels: 8 px at 512, in proportion, at least 2.
int bandRadius(int height);

// One byte per pixel (row 0 at the top), 1 in the band; `obstacles` placed for the frame.
std::vector<uint8_t> obstacleBand(const render::ObstacleBvh& obstacles, const render::Camera& camera,
                                  const render::ImagePlane& plane, int width, int height,
                                  const std::vector<scene::Light>& lights, const HostDensity& smoke,
                                  const BandSettings& settings);

}  // namespace sixway::eval
