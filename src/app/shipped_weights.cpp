#include "app/shipped_weights.h"

namespace sixway::app {

std::filesystem::path resolveWeights(const std::filesystem::path& given) {
  const std::filesystem::path dir(SIXWAY_WEIGHTS_DIR);
  if (given.empty() || given == "ms") return dir / "sixway-unet-ms.safetensors";
  if (given == "ss") return dir / "sixway-unet-ss.safetensors";
  return given;
}

}  // namespace sixway::app
