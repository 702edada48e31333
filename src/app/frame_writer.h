#pragma once
// What `sixway render` leaves in its output directory: frame_NNNN.png (exposed, tone-mapped, sRGB: for
// people) and, with --exr, frame_NNNN.exr (linear half floats, for numbers); at the end a contact sheet of
// the sequence (contact_sheet.png) and, with --video, an H.264 MP4 made by Debian's ffmpeg.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

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
};
inline constexpr int kMaxSheetCells = 64;

class FrameWriter {
 public:
  // Throws io::InputError naming ffmpeg when a video is asked for and ffmpeg is not installed. The run is
  // written into a hidden staging directory inside `directory` (.render.<pid>.partial) and moved into place
  // by commit(), so that a render interrupted or failed half-way leaves an earlier render in `directory`
  // whole.
  FrameWriter(std::filesystem::path directory, const FrameWriterOptions& options);
  ~FrameWriter();  // removes the staging directory unless committed
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Writes frame `index` (RGB or RGBA, linear, alpha ignored in the PNG) and keeps its thumbnail.
  void write(int index, const io::Image& frame);
  // The contact sheet and the video; returns the files written (relative to the directory).
  std::vector<std::string> finish();
  // Where another output of the run (timings.json) is written before commit().
  std::filesystem::path stagedPath(const std::string& name) const { return staging_ / name; }
  // Moves every staged file onto its name in the directory, then removes the outputs of an earlier render
  // that this one did not replace (frame_NNNN.png/.exr, contact_sheet.png, video.mp4, timings.json). Other
  // files in the directory are never touched.
  void commit();

  static std::string frameName(int index);  // "frame_0007"
  // Whether `name` is a file that `sixway render` writes.
  static bool isRenderOutput(const std::string& name);

 private:
  void removeStagingOfKilledRuns() const;
  void underFinalNames(const std::function<void()>& write) const;

  std::filesystem::path directory_;
  std::filesystem::path staging_;
  FrameWriterOptions options_;
  std::vector<io::Image> thumbnails_;
  bool committed_ = false;
  bool createdDirectory_ = false;
};

}  // namespace sixway::app
