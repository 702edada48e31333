#pragma once
// What `sixway render` leaves in its output directory: frame_NNNN.png (sRGB, for people) and, with --exr,
// frame_NNNN.exr (linear half floats, for numbers); at the end a contact sheet of the sequence
// (contact_sheet.png) and, with --video, an H.264 MP4 made by Debian's ffmpeg.
#include <filesystem>
#include <string>
#include <vector>

#include "io/image.h"

namespace sixway::app {

struct FrameWriterOptions {
  bool exr = false;
  bool video = false;
  int fps = 30;
  int thumbnailWidth = 160;  // of each contact-sheet cell, pixels
  // Frames the sequence will have: the contact sheet shows at most kMaxSheetCells of them, evenly spaced, so
  // a run of 10,000 frames keeps 64 thumbnails in memory, not 10,000.
  int frames = 0;
};
inline constexpr int kMaxSheetCells = 64;

class FrameWriter {
 public:
  // Throws io::InputError naming ffmpeg when a video is asked for and ffmpeg is not installed. Removes the
  // frames of an earlier render in `directory` (the command line has checked --force).
  FrameWriter(std::filesystem::path directory, const FrameWriterOptions& options);

  // Writes frame `index` (RGB or RGBA, linear, alpha ignored in the PNG) and keeps its thumbnail.
  void write(int index, const io::Image& frame);
  // The contact sheet and the video; returns the files written (relative to the directory).
  std::vector<std::string> finish();

  static std::string frameName(int index);  // "frame_0007"

 private:
  std::filesystem::path directory_;
  FrameWriterOptions options_;
  std::vector<io::Image> thumbnails_;
};

}  // namespace sixway::app
