#include "io/error.h"

namespace sixway::io {

InputError::InputError(std::string_view source, std::string_view problem)
    : std::runtime_error(std::string(source) + ": " + std::string(problem)) {}

}  // namespace sixway::io
