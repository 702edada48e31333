#include "io/safetensors.h"

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "io/error.h"
#include "io/file_access.h"
#include "io/json_reader.h"

namespace sixway::io {

// Tensor bytes are little-endian in the file and are used in place.
static_assert(std::endian::native == std::endian::little, "safetensors support assumes a little-endian host");

namespace {

using nlohmann::json;

// A limit against absurd header lengths (the reference implementation uses the same).
constexpr uint64_t kMaxHeaderBytes = 100'000'000;
constexpr std::string_view kMetadataKey = "__metadata__";

struct DTypeInfo {
  DType dtype;
  std::string_view name;
  std::size_t size;
};
constexpr std::array<DTypeInfo, 6> kDTypes = {{{DType::F32, "F32", 4},
                                               {DType::F16, "F16", 2},
                                               {DType::BF16, "BF16", 2},
                                               {DType::I32, "I32", 4},
                                               {DType::I64, "I64", 8},
                                               {DType::U8, "U8", 1}}};

const DTypeInfo& infoOf(DType dtype) {
  return *std::find_if(kDTypes.begin(), kDTypes.end(), [&](const DTypeInfo& i) { return i.dtype == dtype; });
}

std::optional<DType> parseDType(std::string_view name) {
  for (const DTypeInfo& info : kDTypes) {
    if (info.name == name) return info.dtype;
  }
  return std::nullopt;
}

std::string supportedDTypes() {
  std::string list;
  for (const DTypeInfo& info : kDTypes) list += (list.empty() ? "" : ", ") + std::string(info.name);
  return list;
}

float bf16ToFloat(uint16_t bits) {
  return std::bit_cast<float>(static_cast<uint32_t>(bits) << 16);
}

uint16_t floatToBf16(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  if (value != value) return static_cast<uint16_t>((bits >> 16) | 0x40);  // keep NaN a (quiet) NaN
  const uint32_t roundToNearestEven = 0x7FFF + ((bits >> 16) & 1);
  return static_cast<uint16_t>((bits + roundToNearestEven) >> 16);
}

std::string shapeText(const std::vector<int64_t>& shape) {
  std::string text = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

// The value as int64 when it is a JSON integer that fits.
std::optional<int64_t> asInt64(const json& value) {
  if (value.is_number_unsigned()) {
    const uint64_t u = value.get<uint64_t>();
    if (u > static_cast<uint64_t>(INT64_MAX)) return std::nullopt;
    return static_cast<int64_t>(u);
  }
  if (value.is_number_integer()) return value.get<int64_t>();
  return std::nullopt;
}

// The product of the dimensions, or nothing when it overflows.
std::optional<uint64_t> checkedElementCount(const std::vector<int64_t>& shape) {
  uint64_t count = 1;
  for (int64_t dim : shape) {
    if (__builtin_mul_overflow(count, static_cast<uint64_t>(dim), &count)) return std::nullopt;
  }
  return count;
}

struct PlacedTensor {
  Tensor tensor;
  uint64_t begin = 0;
  uint64_t end = 0;
};

PlacedTensor parseTensorEntry(const std::string& source, const std::string& name, const json& entry,
                              uint64_t dataSize) {
  const std::string where = "tensor '" + name + "': ";
  if (!entry.is_object()) throw InputError(source, where + "entry is not a JSON object");
  for (const char* key : {"dtype", "shape", "data_offsets"}) {
    if (!entry.contains(key)) throw InputError(source, where + "missing \"" + key + "\"");
  }
  PlacedTensor placed;
  placed.tensor.name = name;

  const json& dtype = entry["dtype"];
  if (!dtype.is_string()) throw InputError(source, where + "\"dtype\" is not a string");
  const std::optional<DType> parsedDType = parseDType(dtype.get<std::string>());
  if (!parsedDType) {
    throw InputError(source, where + "unsupported dtype \"" + dtype.get<std::string>() +
                                 "\" (supported: " + supportedDTypes() + ")");
  }
  placed.tensor.dtype = *parsedDType;

  const json& shape = entry["shape"];
  if (!shape.is_array()) throw InputError(source, where + "\"shape\" is not an array of integers");
  for (const json& dim : shape) {
    const std::optional<int64_t> value = asInt64(dim);
    if (!value) throw InputError(source, where + "\"shape\" is not an array of integers");
    if (*value < 0) {
      throw InputError(source, where + "negative dimension " + std::to_string(*value) + " in shape");
    }
    placed.tensor.shape.push_back(*value);
  }

  const json& offsets = entry["data_offsets"];
  const bool offsetsArePair = offsets.is_array() && offsets.size() == 2 &&
                              asInt64(offsets[0]).value_or(-1) >= 0 && asInt64(offsets[1]).value_or(-1) >= 0;
  if (!offsetsArePair) {
    throw InputError(source, where + "\"data_offsets\" is not [begin, end] with non-negative integers");
  }
  placed.begin = static_cast<uint64_t>(*asInt64(offsets[0]));
  placed.end = static_cast<uint64_t>(*asInt64(offsets[1]));
  if (placed.begin > placed.end) {
    throw InputError(source, where + "data_offsets begin " + std::to_string(placed.begin) + " is after end " +
                                 std::to_string(placed.end));
  }
  if (placed.end > dataSize) {
    throw InputError(source, where + "data_offsets end " + std::to_string(placed.end) +
                                 " is past the end of the data (" + std::to_string(dataSize) + " bytes)");
  }

  const std::optional<uint64_t> count = checkedElementCount(placed.tensor.shape);
  uint64_t expectedBytes = 0;
  if (!count || __builtin_mul_overflow(*count, dtypeSize(placed.tensor.dtype), &expectedBytes)) {
    throw InputError(source, where + "shape " + shapeText(placed.tensor.shape) + " is too large");
  }
  if (expectedBytes != placed.end - placed.begin) {
    throw InputError(source, where + std::to_string(placed.end - placed.begin) + " bytes of data, but " +
                                 std::string(dtypeName(placed.tensor.dtype)) + " " +
                                 shapeText(placed.tensor.shape) + " needs " + std::to_string(expectedBytes));
  }
  return placed;
}

std::map<std::string, std::string> parseMetadata(const std::string& source, const json& metadata) {
  if (!metadata.is_object()) throw InputError(source, "\"__metadata__\" is not a JSON object");
  std::map<std::string, std::string> result;
  for (const auto& [key, value] : metadata.items()) {
    if (!value.is_string()) {
      throw InputError(source, "\"__metadata__\" value of '" + key + "' is not a string");
    }
    result[key] = value.get<std::string>();
  }
  return result;
}

// The format requires the tensors to tile the data buffer exactly: no overlaps, no holes, nothing after
// the end.
void checkLayout(const std::string& source, const std::vector<PlacedTensor>& sortedByBegin,
                 uint64_t dataSize) {
  uint64_t covered = 0;
  const PlacedTensor* previous = nullptr;
  for (const PlacedTensor& placed : sortedByBegin) {
    if (placed.begin < covered) {
      throw InputError(source, "tensors '" + previous->tensor.name + "' and '" + placed.tensor.name +
                                   "' overlap in the data buffer");
    }
    if (placed.begin > covered) {
      throw InputError(source, "bytes " + std::to_string(covered) + " to " + std::to_string(placed.begin) +
                                   " of the data buffer belong to no tensor");
    }
    covered = placed.end;
    previous = &placed;
  }
  if (covered != dataSize) {
    throw InputError(source, "bytes " + std::to_string(covered) + " to " + std::to_string(dataSize) +
                                 " of the data buffer belong to no tensor");
  }
}

void putU64LittleEndian(uint64_t value, std::ostream& out) {
  std::array<char, 8> bytes;
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<char>((value >> (8 * i)) & 0xFF);
  out.write(bytes.data(), bytes.size());
}

}  // namespace

std::size_t dtypeSize(DType dtype) {
  return infoOf(dtype).size;
}

std::string_view dtypeName(DType dtype) {
  return infoOf(dtype).name;
}

int64_t Tensor::elementCount() const {
  int64_t count = 1;
  for (int64_t dim : shape) count *= dim;
  return count;
}

std::vector<float> Tensor::toFloat() const {
  const std::size_t count = bytes.size() / dtypeSize(dtype);
  std::vector<float> values(count);
  switch (dtype) {
    case DType::F32:
      std::memcpy(values.data(), bytes.data(), count * sizeof(float));
      return values;
    case DType::F16:
    case DType::BF16:
      for (std::size_t i = 0; i < count; ++i) {
        uint16_t bits;
        std::memcpy(&bits, bytes.data() + 2 * i, 2);
        if (dtype == DType::F16) {
          Imath::half half;
          half.setBits(bits);
          values[i] = half;
        } else {
          values[i] = bf16ToFloat(bits);
        }
      }
      return values;
    default:
      throw std::logic_error("tensor '" + name + "' is " + std::string(dtypeName(dtype)) +
                             ", not a floating-point type");
  }
}

Tensor Tensor::fromFloat(std::string name, DType dtype, std::vector<int64_t> shape,
                         std::span<const float> values) {
  Tensor tensor{std::move(name), dtype, std::move(shape), {}};
  if (static_cast<std::size_t>(tensor.elementCount()) != values.size()) {
    throw std::invalid_argument("tensor '" + tensor.name + "': " + std::to_string(values.size()) +
                                " values for shape " + shapeText(tensor.shape));
  }
  tensor.bytes.resize(values.size() * dtypeSize(dtype));
  for (std::size_t i = 0; i < values.size(); ++i) {
    switch (dtype) {
      case DType::F32:
        std::memcpy(tensor.bytes.data() + 4 * i, &values[i], 4);
        break;
      case DType::F16: {
        const uint16_t bits = Imath::half(values[i]).bits();
        std::memcpy(tensor.bytes.data() + 2 * i, &bits, 2);
        break;
      }
      case DType::BF16: {
        const uint16_t bits = floatToBf16(values[i]);
        std::memcpy(tensor.bytes.data() + 2 * i, &bits, 2);
        break;
      }
      default:
        throw std::invalid_argument("tensor '" + tensor.name + "': fromFloat needs F32, F16 or BF16, not " +
                                    std::string(dtypeName(dtype)));
    }
  }
  return tensor;
}

bool SafetensorsFile::contains(std::string_view name) const {
  return std::any_of(tensors.begin(), tensors.end(), [&](const Tensor& t) { return t.name == name; });
}

const Tensor& SafetensorsFile::at(std::string_view name) const {
  for (const Tensor& tensor : tensors) {
    if (tensor.name == name) return tensor;
  }
  throw InputError(path.string(), "missing tensor '" + std::string(name) + "'");
}

SafetensorsFile readSafetensors(const std::filesystem::path& path) {
  return parseSafetensors(readFileBytes(path), path);
}

SafetensorsFile parseSafetensors(std::span<const uint8_t> file, const std::filesystem::path& path) {
  const std::string source = path.string();
  if (file.size() < 8) {
    throw InputError(
        source, "file is " + std::to_string(file.size()) + " bytes, too short for the 8-byte header length");
  }
  uint64_t headerLength = 0;
  for (int i = 7; i >= 0; --i) headerLength = (headerLength << 8) | file[i];
  if (headerLength > kMaxHeaderBytes) {
    throw InputError(source, "header length " + std::to_string(headerLength) + " is over the limit of " +
                                 std::to_string(kMaxHeaderBytes) + " bytes");
  }
  if (headerLength > file.size() - 8) {
    throw InputError(source, "header length " + std::to_string(headerLength) +
                                 " runs past the end of the file (" + std::to_string(file.size()) +
                                 " bytes)");
  }

  const auto headerBegin = file.begin() + 8;
  const auto dataBegin = headerBegin + static_cast<std::ptrdiff_t>(headerLength);
  json header;
  try {
    // A header nested past kMaxJsonNesting is refused as it is read: printing it would overflow the stack.
    const std::string_view headerText(reinterpret_cast<const char*>(file.data()) + 8, headerLength);
    header = parseJsonChecked(headerText, [&source](int depth, JsonEvent, std::string_view) {
      if (depth >= kMaxJsonNesting)  // depth counts from 0: N nested levels reach N − 1
        throw InputError(source,
                         "header is nested deeper than " + std::to_string(kMaxJsonNesting) + " levels");
    });
  } catch (const json::parse_error& error) {
    throw InputError(
        source, "header is not valid JSON (error at byte " + std::to_string(error.byte) + " of the header)");
  } catch (const json::out_of_range&) {  // a number beyond double, e.g. 1e999
    throw InputError(source, "header is not valid JSON (a number is out of range)");
  }
  if (!header.is_object()) throw InputError(source, "header is not a JSON object");

  const uint64_t dataSize = static_cast<uint64_t>(file.end() - dataBegin);
  SafetensorsFile result;
  result.path = path;
  std::vector<PlacedTensor> placed;
  for (const auto& [key, value] : header.items()) {
    if (key == kMetadataKey) {
      result.metadata = parseMetadata(source, value);
    } else {
      placed.push_back(parseTensorEntry(source, key, value, dataSize));
    }
  }
  // By end too, so that an empty tensor sorts before a tensor that starts at the same offset.
  std::sort(placed.begin(), placed.end(), [](const PlacedTensor& a, const PlacedTensor& b) {
    return std::pair(a.begin, a.end) < std::pair(b.begin, b.end);
  });
  checkLayout(source, placed, dataSize);

  for (PlacedTensor& entry : placed) {
    entry.tensor.bytes.assign(dataBegin + static_cast<std::ptrdiff_t>(entry.begin),
                              dataBegin + static_cast<std::ptrdiff_t>(entry.end));
    result.tensors.push_back(std::move(entry.tensor));
  }
  return result;
}

void writeSafetensors(const std::filesystem::path& path, const std::vector<Tensor>& tensors,
                      const std::map<std::string, std::string>& metadata) {
  const std::string source = path.string();
  // Ordered so that the header lists the tensors in data order, after the metadata.
  nlohmann::ordered_json header = nlohmann::ordered_json::object();
  if (!metadata.empty()) header[std::string(kMetadataKey)] = metadata;
  uint64_t offset = 0;
  for (const Tensor& tensor : tensors) {
    if (tensor.name.empty() || tensor.name == kMetadataKey || header.contains(tensor.name)) {
      throw InputError(source,
                       "cannot write a tensor named '" + tensor.name + "' (empty, reserved or repeated)");
    }
    const bool negativeDim =
        std::any_of(tensor.shape.begin(), tensor.shape.end(), [](int64_t d) { return d < 0; });
    if (negativeDim || tensor.bytes.size() != tensor.elementCount() * dtypeSize(tensor.dtype)) {
      throw InputError(source, "tensor '" + tensor.name + "': " + std::to_string(tensor.bytes.size()) +
                                   " bytes do not match " + std::string(dtypeName(tensor.dtype)) + " " +
                                   shapeText(tensor.shape));
    }
    header[tensor.name] = {{"dtype", dtypeName(tensor.dtype)},
                           {"shape", tensor.shape},
                           {"data_offsets", {offset, offset + tensor.bytes.size()}}};
    offset += tensor.bytes.size();
  }

  std::string headerText;
  try {
    headerText = header.dump();
  } catch (const nlohmann::json::type_error&) {
    throw InputError(source, "a tensor name or metadata string is not valid UTF-8");
  }
  headerText.append((8 - headerText.size() % 8) % 8, ' ');

  AtomicFile file(path);
  {
    std::ofstream out(file.temporaryPath(), std::ios::binary);
    putU64LittleEndian(headerText.size(), out);
    out.write(headerText.data(), static_cast<std::streamsize>(headerText.size()));
    for (const Tensor& tensor : tensors) {
      out.write(reinterpret_cast<const char*>(tensor.bytes.data()),
                static_cast<std::streamsize>(tensor.bytes.size()));
    }
    // Shards reach 4 GiB, so they stream rather than go through AtomicFile::writeAll; errno holds the
    // failed write's reason (ENOSPC on a full disk).
    if (!out.flush()) throw InputError(source, std::string("cannot write the file: ") + std::strerror(errno));
  }
  file.commit();
}

}  // namespace sixway::io
