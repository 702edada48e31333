#include "dataset/planar_tensor.h"

#include <cstring>
#include <utility>

namespace sixway::dataset {

PlanarTensor::PlanarTensor(std::string name, int samples, int channels, int size)
    : name_(std::move(name)),
      channels_(channels),
      size_(size),
      bytes_(size_t(samples) * channels * size * size * 2, 0) {}

void PlanarTensor::set(int sample, const std::vector<float>& image, int stride) {
  const size_t plane = size_t(size_) * size_;
  std::vector<float> planar(plane * channels_);
  for (int c = 0; c < channels_; ++c)
    for (size_t i = 0; i < plane; ++i) planar[c * plane + i] = image[i * stride + c];
  const io::Tensor half = io::Tensor::fromFloat("", io::DType::F16, {int64_t(planar.size())}, planar);
  std::memcpy(bytes_.data() + size_t(sample) * half.bytes.size(), half.bytes.data(), half.bytes.size());
}

io::Tensor PlanarTensor::take(int samples) {
  return {name_, io::DType::F16, {samples, channels_, size_, size_}, std::move(bytes_)};
}

}  // namespace sixway::dataset
