// What a smoke instance costs: the device memory of the first and of a second instance of a scene (sharing
// the first's network, and with a network of its own), and the time of a frame (simulation and rendering into
// sixway's own image) with one and with two, wall clock and summed GPU stage times, each over 4 frames after
// a warm-up frame. docs/embedding.md, "Measured".
//   instance_cost SCENE.json WEIGHTS.safetensors
#include <sixway/device.h>
#include <sixway/smoke_renderer.h>
#include <sixway/smoke_simulation.h>
#include <chrono>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

int measure(int argc, char** argv);

int main(int argc, char** argv) {
  try {
    return measure(argc, argv);
  } catch (const std::exception& e) {  // sixway::Error: one line naming the file
    std::fprintf(stderr, "instance_cost: %s\n", e.what());
    return 1;
  }
}

int measure(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: instance_cost SCENE.json WEIGHTS.safetensors\n");
    return 2;
  }
  const std::string scene = argv[1], weights = argv[2];
  const int frames = 4;
  sixway::Device device;
  const auto before = device.memoryUse();
  auto simA = std::make_unique<sixway::SmokeSimulation>(device, scene);
  auto renA =
      std::make_unique<sixway::SmokeRenderer>(device, *simA, sixway::RendererOptions{.weights = weights});
  simA->advance();
  renA->render();
  const auto one = device.memoryUse();
  auto time = [&](bool both, sixway::SmokeSimulation* simB, sixway::SmokeRenderer* renB) {
    double gpu = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
      simA->advance();
      renA->render();
      for (auto& t : simA->stageTimes()) gpu += t.milliseconds;
      for (auto& t : renA->stageTimes()) gpu += t.milliseconds;
      if (both) {
        simB->advance();
        renB->render();
        for (auto& t : simB->stageTimes()) gpu += t.milliseconds;
        for (auto& t : renB->stageTimes()) gpu += t.milliseconds;
      }
    }
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return std::make_pair(wall / frames, gpu / frames);
  };
  const auto single = time(false, nullptr, nullptr);
  auto simB = std::make_unique<sixway::SmokeSimulation>(device, scene);
  auto renB = std::make_unique<sixway::SmokeRenderer>(device, *simB,
                                                      sixway::RendererOptions{.shareNetwork = renA.get()});
  simB->advance();
  renB->render();
  const auto two = device.memoryUse();
  const auto pair = time(true, simB.get(), renB.get());
  {
    sixway::SmokeSimulation simC(device, scene);
    sixway::SmokeRenderer renC(device, simC, {.weights = weights});
    simC.advance();
    renC.render();
    const auto three = device.memoryUse();
    std::printf(
        "%s: first instance %.1f MiB in %llu allocations; second +%.1f MiB in %llu sharing the network, "
        "+%.1f MiB with its own; per frame one %.0f ms wall (%.0f GPU), two %.0f ms wall (%.0f GPU)\n",
        scene.c_str(), (one.bytes - before.bytes) / 1048576.0,
        (unsigned long long)(one.allocations - before.allocations), (two.bytes - one.bytes) / 1048576.0,
        (unsigned long long)(two.allocations - one.allocations), (three.bytes - two.bytes) / 1048576.0,
        single.first, single.second, pair.first, pair.second);
  }
  return 0;
}
