#include "app/device_limits.h"

namespace sixway::app {

std::string gridSetting(const scene::Grid& grid) {
  std::string text = "grid.size (" + std::to_string(grid.size.x) + "×" + std::to_string(grid.size.y) + "×" +
                     std::to_string(grid.size.z) + ")";
  if (grid.smokeUpres > 1) text += " or grid.smoke_upres (" + std::to_string(grid.smokeUpres) + ")";
  return text;
}

}  // namespace sixway::app
