#include "io/error.h"

namespace sixway::io {

InputError::InputError(std::string_view source, std::string_view problem)
    : Error(std::string(source) + ": " + std::string(problem)) {}

}  // namespace sixway::io
