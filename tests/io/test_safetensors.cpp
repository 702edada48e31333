#include "io/safetensors.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace sixway::io {
namespace {

namespace fs = std::filesystem;
using test::inputErrorMessage;
using test::namesFileAndProblem;
using ::testing::ElementsAre;

std::vector<uint8_t> floatBytes(std::initializer_list<float> values) {
  std::vector<uint8_t> bytes(values.size() * sizeof(float));
  std::memcpy(bytes.data(), std::data(values), bytes.size());
  return bytes;
}

std::vector<uint8_t> u16Bytes(std::initializer_list<uint16_t> values) {
  std::vector<uint8_t> bytes;
  for (uint16_t v : values)
    bytes.insert(bytes.end(), {static_cast<uint8_t>(v & 0xFF), static_cast<uint8_t>(v >> 8)});
  return bytes;
}

std::vector<uint16_t> asU16(const std::vector<uint8_t>& bytes) {
  std::vector<uint16_t> values(bytes.size() / 2);
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

std::vector<uint8_t> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class SafetensorsTest : public ::testing::Test {
 protected:
  // A file made byte by byte: `declaredLength` as u64 little-endian, `header`, then `dataBytes` bytes.
  void writeRaw(const std::string& header, std::size_t dataBytes, uint64_t declaredLength) {
    std::ofstream out(file, std::ios::binary);
    for (int i = 0; i < 8; ++i) out.put(static_cast<char>((declaredLength >> (8 * i)) & 0xFF));
    out << header << std::string(dataBytes, '\0');
  }
  void writeRaw(const std::string& header, std::size_t dataBytes) {
    writeRaw(header, dataBytes, header.size());
  }

  std::string readError() {
    return inputErrorMessage([&] { readSafetensors(file); });
  }
  // The error for a file with this header and a data buffer of `dataBytes` zero bytes.
  std::string errorForHeader(const std::string& header, std::size_t dataBytes) {
    writeRaw(header, dataBytes);
    return readError();
  }

  test::TempDir dir;
  fs::path file = dir / "weights.safetensors";
};

TEST_F(SafetensorsTest, ReadsAHandMadeFile) {
  const std::vector<uint8_t> data = floatBytes({1.5f, -2.0f});
  {
    const std::string header =
        R"({"w":{"dtype":"F32","shape":[2],"data_offsets":[0,8]},"__metadata__":{"format":"pt"}})";
    writeRaw(header, 0);
    std::ofstream(file, std::ios::binary | std::ios::app)
        .write(reinterpret_cast<const char*>(data.data()), 8);
  }
  const SafetensorsFile weights = readSafetensors(file);
  ASSERT_EQ(weights.tensors.size(), 1u);
  EXPECT_EQ(weights.at("w").dtype, DType::F32);
  EXPECT_THAT(weights.at("w").shape, ElementsAre(2));
  EXPECT_THAT(weights.at("w").toFloat(), ElementsAre(1.5f, -2.0f));
  EXPECT_EQ(weights.metadata.at("format"), "pt");
}

TEST_F(SafetensorsTest, EmptyTensorMaySitWhereAnotherStarts) {
  const std::string header = R"({"a": {"dtype": "U8", "shape": [4], "data_offsets": [0, 4]},
                                 "b": {"dtype": "U8", "shape": [4], "data_offsets": [4, 8]},
                                 "empty": {"dtype": "F32", "shape": [0], "data_offsets": [4, 4]}})";
  writeRaw(header, 8);
  const SafetensorsFile weights = readSafetensors(file);
  ASSERT_EQ(weights.tensors.size(), 3u);
  EXPECT_TRUE(weights.at("empty").bytes.empty());
}

TEST_F(SafetensorsTest, RoundTripIsBitIdenticalAndAligned) {
  const std::vector<float> matrix = {1, 2, 3, 4, 5, -6.25f};
  const std::vector<float> halves = {0.5f, -1, 65504, 1e-3f};
  const std::vector<float> brains = {3.0f, -0.125f};
  const float scalar = 42.0f;
  const std::vector<Tensor> tensors = {
      Tensor::fromFloat("layer0.weight", DType::F32, {2, 3}, matrix),
      Tensor::fromFloat("layer0.bias", DType::F16, {4}, halves),
      Tensor::fromFloat("bf", DType::BF16, {1, 2}, brains),
      Tensor{"counts", DType::I32, {3}, {1, 0, 0, 0, 2, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF}},
      Tensor{"big", DType::I64, {1}, {1, 2, 3, 4, 5, 6, 7, 8}},
      Tensor{"bytes", DType::U8, {5}, {9, 8, 7, 6, 5}},
      Tensor::fromFloat("scalar", DType::F32, {}, std::span(&scalar, 1)),
      Tensor{"nothing", DType::F32, {0, 3}, {}},
  };
  const std::map<std::string, std::string> metadata = {{"graph", R"({"layers":[{"type":"dense"}]})"},
                                                       {"output_encoding", "srgb"}};
  writeSafetensors(file, tensors, metadata);

  const std::vector<uint8_t> raw = fileBytes(file);
  uint64_t headerLength = 0;
  std::memcpy(&headerLength, raw.data(), 8);
  EXPECT_EQ((8 + headerLength) % 8, 0u) << "data must start 8-byte aligned";

  const SafetensorsFile read = readSafetensors(file);
  EXPECT_EQ(read.metadata, metadata);
  ASSERT_EQ(read.tensors.size(), tensors.size());
  for (std::size_t i = 0; i < tensors.size(); ++i) {
    SCOPED_TRACE(tensors[i].name);
    EXPECT_EQ(read.tensors[i].name, tensors[i].name) << "tensors keep their order";
    EXPECT_EQ(read.tensors[i].dtype, tensors[i].dtype);
    EXPECT_EQ(read.tensors[i].shape, tensors[i].shape);
    EXPECT_EQ(read.tensors[i].bytes, tensors[i].bytes);
  }
  EXPECT_EQ(read.at("layer0.weight").toFloat(), matrix);
  EXPECT_EQ(read.at("layer0.bias").toFloat()[2], 65504.0f);
  EXPECT_EQ(read.at("bf").toFloat(), brains);
  EXPECT_EQ(read.at("scalar").elementCount(), 1);
}

TEST_F(SafetensorsTest, WriteLeavesOnlyTheFinalFile) {
  writeSafetensors(file, {Tensor{"b", DType::U8, {1}, {7}}});
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  EXPECT_TRUE(fs::exists(file));
}

TEST(SafetensorsConversion, F16KnownValues) {
  // 1, -2, the largest half, the smallest subnormal (2^-24) and a larger subnormal (2^-15).
  const Tensor tensor{"h", DType::F16, {5}, u16Bytes({0x3C00, 0xC000, 0x7BFF, 0x0001, 0x0200})};
  EXPECT_THAT(tensor.toFloat(),
              ElementsAre(1.0f, -2.0f, 65504.0f, std::ldexp(1.0f, -24), std::ldexp(1.0f, -15)));
  const std::vector<float> values = tensor.toFloat();
  EXPECT_THAT(asU16(Tensor::fromFloat("h", DType::F16, {5}, values).bytes),
              ElementsAre(0x3C00, 0xC000, 0x7BFF, 0x0001, 0x0200));
}

TEST(SafetensorsConversion, BF16KnownValuesAndRoundToNearestEven) {
  const Tensor tensor{"b", DType::BF16, {2}, u16Bytes({0x3F80, 0xC000})};
  EXPECT_THAT(tensor.toFloat(), ElementsAre(1.0f, -2.0f));
  // 1 + 2^-8 is halfway between 0x3F80 and 0x3F81 (ties to even: 0x3F80); 1 + 3 * 2^-8 rounds up to 0x3F82.
  const std::vector<float> ties = {1.0f + std::ldexp(1.0f, -8), 1.0f + 3 * std::ldexp(1.0f, -8)};
  EXPECT_THAT(asU16(Tensor::fromFloat("b", DType::BF16, {2}, ties).bytes), ElementsAre(0x3F80, 0x3F82));
}

TEST(SafetensorsConversion, IntegerTensorIsNotConvertedToFloat) {
  const Tensor tensor{"i", DType::I32, {1}, {1, 0, 0, 0}};
  EXPECT_THROW(tensor.toFloat(), std::logic_error);
}

TEST_F(SafetensorsTest, AtNamesTheFileAndTheMissingTensor) {
  writeSafetensors(file, {Tensor{"b", DType::U8, {1}, {7}}});
  const SafetensorsFile weights = readSafetensors(file);
  EXPECT_THAT(inputErrorMessage([&] { weights.at("bias"); }),
              namesFileAndProblem(file, "missing tensor 'bias'"));
}

// Bad input: each case names the file and the problem.

TEST_F(SafetensorsTest, MissingFile) {
  EXPECT_THAT(readError(), namesFileAndProblem(file, "no such file"));
}

TEST_F(SafetensorsTest, FileShorterThanTheHeaderLength) {
  std::ofstream(file, std::ios::binary) << "abcde";
  EXPECT_THAT(readError(), namesFileAndProblem(file, "file is 5 bytes, too short"));
}

TEST_F(SafetensorsTest, HeaderLengthPastTheEndOfTheFile) {
  writeRaw("{}", 0, 1000);
  EXPECT_THAT(readError(), namesFileAndProblem(file, "header length 1000 runs past the end of the file"));
}

TEST_F(SafetensorsTest, AbsurdHeaderLength) {
  writeRaw("{}", 0, uint64_t{1} << 40);
  EXPECT_THAT(readError(), namesFileAndProblem(file, "header length 1099511627776 is over the limit"));
}

TEST_F(SafetensorsTest, HeaderIsNotJson) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": )", 0),
              namesFileAndProblem(file, "header is not valid JSON"));
}

TEST_F(SafetensorsTest, HeaderNumberBeyondDouble) {
  EXPECT_THAT(errorForHeader(R"({"w": 1e999})", 0),
              namesFileAndProblem(file, "header is not valid JSON (a number is out of range)"));
}

// A header of 70,000 nested arrays must not crash the error path: it is refused while it is parsed.
TEST_F(SafetensorsTest, DeeplyNestedHeader) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  EXPECT_THAT(errorForHeader(R"({"__metadata__": {"a": )" + deep + "}}", 0),
              namesFileAndProblem(file, "header is nested deeper than 64 levels"));
}

TEST_F(SafetensorsTest, HeaderIsNotAnObject) {
  EXPECT_THAT(errorForHeader("[1, 2]", 0), namesFileAndProblem(file, "header is not a JSON object"));
}

TEST_F(SafetensorsTest, TensorEntryIsNotAnObject) {
  EXPECT_THAT(errorForHeader(R"({"w": 3})", 0),
              namesFileAndProblem(file, "tensor 'w': entry is not a JSON object"));
}

TEST_F(SafetensorsTest, TensorWithoutDtype) {
  EXPECT_THAT(errorForHeader(R"({"w": {"shape": [1], "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': missing \"dtype\""));
}

TEST_F(SafetensorsTest, TensorWithoutShape) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': missing \"shape\""));
}

TEST_F(SafetensorsTest, TensorWithoutDataOffsets) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [1]}})", 4),
              namesFileAndProblem(file, "tensor 'w': missing \"data_offsets\""));
}

TEST_F(SafetensorsTest, DtypeIsNotAString) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": 32, "shape": [1], "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': \"dtype\" is not a string"));
}

TEST_F(SafetensorsTest, ShapeIsNotAnArrayOfIntegers) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [2.5], "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': \"shape\" is not an array of integers"));
}

TEST_F(SafetensorsTest, DataOffsetsAreNotAPairOfIntegers) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [1], "data_offsets": ["0", "4"]}})", 4),
              namesFileAndProblem(file, "tensor 'w': \"data_offsets\" is not [begin, end]"));
}

TEST_F(SafetensorsTest, UnsupportedDtypeF64) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F64", "shape": [1], "data_offsets": [0, 8]}})", 8),
              namesFileAndProblem(file, "tensor 'w': unsupported dtype \"F64\""));
}

TEST_F(SafetensorsTest, UnknownDtype) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "XYZ", "shape": [1], "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': unsupported dtype \"XYZ\""));
}

TEST_F(SafetensorsTest, NegativeShape) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [2, -3], "data_offsets": [0, 4]}})", 4),
              namesFileAndProblem(file, "tensor 'w': negative dimension -3 in shape"));
}

TEST_F(SafetensorsTest, DataOffsetsBeginAfterEnd) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [1], "data_offsets": [8, 4]}})", 8),
              namesFileAndProblem(file, "tensor 'w': data_offsets begin 8 is after end 4"));
}

TEST_F(SafetensorsTest, DataOffsetsPastTheEndOfTheData) {
  EXPECT_THAT(
      errorForHeader(R"({"w": {"dtype": "F32", "shape": [4], "data_offsets": [0, 16]}})", 12),
      namesFileAndProblem(file, "tensor 'w': data_offsets end 16 is past the end of the data (12 bytes)"));
}

TEST_F(SafetensorsTest, OverlappingTensors) {
  const std::string header = R"({"a": {"dtype": "F32", "shape": [2], "data_offsets": [0, 8]},
                                 "b": {"dtype": "F32", "shape": [2], "data_offsets": [4, 12]}})";
  EXPECT_THAT(errorForHeader(header, 12), namesFileAndProblem(file, "tensors 'a' and 'b' overlap"));
}

TEST_F(SafetensorsTest, DataBytesThatBelongToNoTensor) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [1], "data_offsets": [0, 4]}})", 12),
              namesFileAndProblem(file, "bytes 4 to 12 of the data buffer belong to no tensor"));
}

TEST_F(SafetensorsTest, ByteCountDoesNotMatchDtypeAndShape) {
  EXPECT_THAT(errorForHeader(R"({"w": {"dtype": "F32", "shape": [3], "data_offsets": [0, 8]}})", 8),
              namesFileAndProblem(file, "tensor 'w': 8 bytes of data, but F32 [3] needs 12"));
}

TEST_F(SafetensorsTest, MetadataValueIsNotAString) {
  EXPECT_THAT(errorForHeader(R"({"__metadata__": {"epochs": 12}})", 0),
              namesFileAndProblem(file, "\"__metadata__\" value of 'epochs' is not a string"));
}

TEST_F(SafetensorsTest, MetadataIsNotAnObject) {
  EXPECT_THAT(errorForHeader(R"({"__metadata__": "graph"})", 0),
              namesFileAndProblem(file, "\"__metadata__\" is not a JSON object"));
}

TEST_F(SafetensorsTest, WriteIntoAMissingDirectory) {
  const fs::path target = dir / "no" / "such" / "weights.safetensors";
  EXPECT_THAT(inputErrorMessage([&] { writeSafetensors(target, {}); }),
              namesFileAndProblem(target, "does not exist"));
}

TEST_F(SafetensorsTest, WriteRejectsBytesThatDoNotMatchTheShape) {
  EXPECT_THAT(inputErrorMessage([&] {
                writeSafetensors(file, {Tensor{"w", DType::F32, {2}, {0, 0, 0, 0}}});
              }),
              namesFileAndProblem(file, "tensor 'w': 4 bytes do not match F32 [2]"));
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace sixway::io
