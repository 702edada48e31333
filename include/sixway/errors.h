#pragma once
// What sixway throws. Every error is a sixway::Error whose what() is one line naming the file, option or
// setting at fault and the problem, e.g. "plume.json: grid.size: axis x has 100000 cells, more than 2048;
// reduce grid.size". Bad input, device limits, Vulkan failures and a diverging simulation are all Errors;
// a caller's misuse of the API (a null handle, a size of 0) is std::invalid_argument.
#include <stdexcept>

namespace sixway {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace sixway
