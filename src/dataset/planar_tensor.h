#pragma once
// An F16 tensor [samples, channels, size, size] of a dataset shard, filled sample by sample from interleaved
// float images.
#include <cstdint>
#include <string>
#include <vector>

#include "io/safetensors.h"

namespace sixway::dataset {

class PlanarTensor {
 public:
  PlanarTensor(std::string name, int samples, int channels, int size);

  // `image` holds at least the tensor's channels interleaved per pixel (`stride` values per pixel).
  void set(int sample, const std::vector<float>& image, int stride);
  // The tensor of the first `samples` samples; the PlanarTensor is empty afterwards.
  io::Tensor take(int samples);

 private:
  std::string name_;
  int channels_, size_;
  std::vector<uint8_t> bytes_;
};

}  // namespace sixway::dataset
