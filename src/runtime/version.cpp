#include <sixway/version.h>

namespace sixway {

Version version() {
  return {SIXWAY_VERSION_MAJOR, SIXWAY_VERSION_MINOR, SIXWAY_VERSION_PATCH};
}

}  // namespace sixway
