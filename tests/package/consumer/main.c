/* An engine's C program against the installed sixway: the C API (sixway.h) renders two frames of smoke on
 * sixway's own device, and a bad call fails with a code and a message instead of throwing.
 *   consumer_c SCENE.json WEIGHTS.safetensors */
#include <sixway/sixway.h>
#include <stdio.h>
#include <stdlib.h>

static int failed(SixwayResult result, const char* call) {
  if (result == SIXWAY_SUCCESS) return 0;
  fprintf(stderr, "%s failed (%d): %s\n", call, (int)result, sixwayLastError());
  return 1;
}

int main(int argc, char** argv) {
  SixwayDevice device = NULL;
  SixwaySimulation simulation = NULL;
  SixwayRenderer renderer = NULL;
  uint32_t major = 0, minor = 0, patch = 0, width = 0, height = 0;
  float* pixels = NULL;
  float brightest = 0.0f;
  size_t i, count;
  int status = 1;
  if (argc != 3) {
    fprintf(stderr, "usage: consumer_c SCENE.json WEIGHTS.safetensors\n");
    return 2;
  }
  sixwayVersion(&major, &minor, &patch);
  if (major != SIXWAY_VERSION_MAJOR || minor != SIXWAY_VERSION_MINOR || patch != SIXWAY_VERSION_PATCH) {
    fprintf(stderr, "version mismatch\n");
    return 1;
  }
  if (failed(sixwayCreateOwnDevice(0, &device), "sixwayCreateOwnDevice")) return 1;
  if (sixwayCreateSimulation(device, "no/such/scene.json", &simulation) != SIXWAY_ERROR ||
      sixwayLastError()[0] == '\0') {
    fprintf(stderr, "a missing scene was not an error with a message\n");
    goto done;
  }
  if (failed(sixwayCreateSimulation(device, argv[1], &simulation), "sixwayCreateSimulation") ||
      failed(sixwayCreateRenderer(device, simulation, argv[2], NULL, &renderer), "sixwayCreateRenderer") ||
      failed(sixwaySimulationAdvance(simulation), "sixwaySimulationAdvance") ||
      failed(sixwaySimulationAdvance(simulation), "sixwaySimulationAdvance") ||
      failed(sixwayRendererRender(renderer), "sixwayRendererRender") ||
      failed(sixwayRendererSize(renderer, &width, &height), "sixwayRendererSize"))
    goto done;
  count = (size_t)width * height * 4;
  pixels = malloc(count * sizeof(float));
  if (!pixels || failed(sixwayRendererImage(renderer, pixels, count), "sixwayRendererImage")) goto done;
  for (i = 0; i < count; ++i)
    if (pixels[i] > brightest) brightest = pixels[i];
  if (!(brightest > 0.0f)) {
    fprintf(stderr, "an empty frame\n");
    goto done;
  }
  printf("sixway %u.%u.%u from C: %ux%u frame with smoke (brightest value %.3f)\n", major, minor, patch,
         width, height, brightest);
  status = 0;
done:
  free(pixels);
  sixwayDestroyRenderer(renderer);
  sixwayDestroySimulation(simulation);
  sixwayDestroyDevice(device);
  return status;
}
