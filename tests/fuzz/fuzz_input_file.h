#pragma once
// Our loaders read files by path, so a fuzz input is written to a file first. Each fuzzer process has its own
// scratch folder (removed at exit): fixtures a parser refers to (a base scene, textures) are put there once,
// and each input is written over the same file name.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace sixway::fuzz {

// The scratch folder of this process, made on first use.
const std::filesystem::path& scratchDirectory();

// Writes `size` bytes to scratchDirectory()/name and returns the path.
std::filesystem::path writeInput(const std::string& name, const uint8_t* data, std::size_t size);

}  // namespace sixway::fuzz
