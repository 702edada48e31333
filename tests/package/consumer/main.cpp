// An engine's program against the installed sixway: the package's version, the headers' and the library's
// agree, and two frames of smoke render on sixway's own device.
//   consumer SCENE.json WEIGHTS.safetensors
#include <sixway/device.h>
#include <sixway/errors.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>
#include <sixway/version.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#ifndef PACKAGE_VERSION  // built by hand with pkg-config
#define PACKAGE_VERSION ""
#endif

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: consumer SCENE.json WEIGHTS.safetensors\n");
    return 2;
  }
  const sixway::Version v = sixway::version();
  const std::string linked =
      std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.patch);
  const std::string headers = std::to_string(SIXWAY_VERSION_MAJOR) + "." + std::to_string(SIXWAY_VERSION_MINOR) +
                              "." + std::to_string(SIXWAY_VERSION_PATCH);
  if (linked != headers || (std::string(PACKAGE_VERSION) != "" && headers != PACKAGE_VERSION)) {
    std::fprintf(stderr, "version mismatch: library %s, headers %s, package %s\n", linked.c_str(),
                 headers.c_str(), PACKAGE_VERSION);
    return 1;
  }
  try {
    sixway::Device device;
    sixway::SmokeSimulation simulation(device, argv[1]);
    sixway::SmokeRenderer renderer(device, simulation, {.weights = argv[2]});
    for (int frame = 0; frame < 2; ++frame) simulation.advance();
    renderer.render();
    const std::vector<float> image = renderer.image();
    const float brightest = *std::max_element(image.begin(), image.end());
    if (!(brightest > 0.0f)) {
      std::fprintf(stderr, "an empty frame\n");
      return 1;
    }
    std::printf("sixway %s: %ux%u frame with smoke (brightest value %.3f)\n", linked.c_str(), renderer.width(),
                renderer.height(), brightest);
  } catch (const sixway::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
