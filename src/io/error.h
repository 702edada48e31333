#pragma once
// The one error type for bad input: its message is a single line that names the file
// (or the option) and the problem, printed as is by the command line.
#include <sixway/errors.h>
#include <string>
#include <string_view>

namespace sixway::io {

class InputError : public Error {
 public:
  InputError(std::string_view source, std::string_view problem);
};

}  // namespace sixway::io
