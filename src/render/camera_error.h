#pragma once
// A camera that cannot see its volume (the volume behind it, or reaching behind it): an io::InputError from
// "camera". A command that knows which scene placed the camera names the file (app::namingScene).
#include <string_view>

#include "io/error.h"

namespace sixway::render {

class CameraError : public io::InputError {
 public:
  explicit CameraError(std::string_view problem) : io::InputError("camera", problem) {}
};

}  // namespace sixway::render
