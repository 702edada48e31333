#pragma once
// Safetensors files (the format of the network weights): a u64 little-endian header length N, N bytes of JSON
// header, then the data buffer. The header maps each tensor name to {"dtype", "shape", "data_offsets"}
// (offsets relative to the start of the data buffer) and may hold "__metadata__", a map of strings to
// strings.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sixway::io {

enum class DType { F32, F16, BF16, I32, I64, U8 };

std::size_t dtypeSize(DType dtype);
std::string_view dtypeName(DType dtype);  // as written in the header: "F32", "F16", ...

struct Tensor {
  std::string name;
  DType dtype = DType::F32;
  std::vector<int64_t> shape;  // empty for a scalar
  std::vector<uint8_t> bytes;  // row-major, little-endian

  int64_t elementCount() const;
  // The values as floats; F32, F16 and BF16 only (std::logic_error for the integer types).
  std::vector<float> toFloat() const;
  // An F32, F16 or BF16 tensor of `values` (16-bit types round to nearest even); std::invalid_argument when
  // the dtype is an integer type or the value count does not match the shape.
  static Tensor fromFloat(std::string name, DType dtype, std::vector<int64_t> shape,
                          std::span<const float> values);
};

struct SafetensorsFile {
  std::filesystem::path path;
  std::map<std::string, std::string> metadata;
  std::vector<Tensor> tensors;  // in data-buffer order

  bool contains(std::string_view name) const;
  // Throws InputError "<path>: missing tensor '<name>'".
  const Tensor& at(std::string_view name) const;
};

// Throws InputError naming the file and the problem for any malformed input.
SafetensorsFile readSafetensors(const std::filesystem::path& path);
// The same for a file's bytes held in memory; `path` names them in errors and in the result.
SafetensorsFile parseSafetensors(std::span<const uint8_t> bytes, const std::filesystem::path& path);

// Tensors are laid out in the given order; the header is padded with spaces so that the data starts 8-byte
// aligned. Throws InputError naming the file when it cannot be written or a tensor is inconsistent.
void writeSafetensors(const std::filesystem::path& path, const std::vector<Tensor>& tensors,
                      const std::map<std::string, std::string>& metadata = {});

}  // namespace sixway::io
