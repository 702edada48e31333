#pragma once
// What a sixway::SmokeSimulation holds: its scene and the simulated volumes on the device.
#include <sixway/smoke_simulation.h>

#include "io/scene.h"
#include "runtime/device_impl.h"
#include "runtime/scene_volumes.h"

namespace sixway {

struct SmokeSimulation::Impl {
  Impl(Device::Impl& device, io::Scene scene);
  Device::Impl& device;
  io::Scene scene;
  runtime::SimulatedVolumes volumes;
  int frames = 0;  // frames simulated (or recorded)
};

}  // namespace sixway
