#pragma once
// What `sixway render` leaves in its output directory: frame_NNNN.png (exposed, tone-mapped, sRGB: for
// people) and, with --exr, frame_NNNN.exr (linear half floats, for numbers); at the end a contact sheet of
// the sequence (contact_sheet.png) and, with --video, an H.264 MP4 made by Debian's ffmpeg.
#include <filesystem>
#include <string>
#include <vector>

#include "app/staged_directory.h"
#include "app/tone_map.h"
#include "io/image.h"

namespace sixway::app {

struct FrameWriterOptions {
  bool exr = false;
  bool video = false;
  int fps = 30;
  DisplayTransform display;  // of the PNG frames, contact sheet and video (the EXR is linear)
  int thumbnailWidth = 160;  // of each contact-sheet cell, pixels
  // Frames the sequence will have: the contact sheet shows at most kMaxSheetCells of them, evenly spaced, so
  // a run of 10,000 frames keeps 64 thumbnails in memory, not 10,000.
  int frames = 0;
  // Write into an existing output directory (--force); without it the run must be the one that makes it.
  bool force = false;
};
inline constexpr int kMaxSheetCells = 64;

class FrameWriter {
 public:
  // Throws io::InputError naming ffmpeg when a video is asked for and ffmpeg is not installed, or naming
  // `directory` when it cannot be claimed (StagedDirectory). The run is written into a hidden staging
  // directory inside `directory` (.render.<pid>.partial) and moved into place by commit(), so that a render
  // interrupted or failed half-way leaves an earlier render in `directory` whole.
  FrameWriter(std::filesystem::path directory, const FrameWriterOptions& options);
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Writes frame `index` (RGB or RGBA, linear, alpha ignored in the PNG) and keeps its thumbnail.
  void write(int index, const io::Image& frame);
  // The contact sheet and the video; returns the files written (relative to the directory).
  std::vector<std::string> finish();
  // Where another output of the run (timings.json) is written before commit().
  std::filesystem::path stagedPath(const std::string& name) const { return output_.stagedPath(name); }
  // All or nothing (StagedDirectory::commit): moves every staged file onto its name in the directory, then
  // removes the outputs of an earlier render that this one did not replace (frame_NNNN.png/.exr,
  // contact_sheet.png, video.mp4, timings.json); a directory or special file under one of those names is an
  // error before anything is moved. Other files in the directory are never touched.
  void commit() { output_.commit(); }

  static std::string frameName(int index);  // "frame_0007"
  // Whether `name` is a file that `sixway render` writes.
  static bool isRenderOutput(const std::string& name);

 private:
  FrameWriterOptions options_;
  StagedDirectory output_;
  std::vector<io::Image> thumbnails_;
};

}  // namespace sixway::app
