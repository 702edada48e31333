#include "app/frame_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "io/error.h"
#include "io/exr.h"
#include "io/file_access.h"
#include "io/png.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

// RGB of `frame`, box-filtered down to `width` pixels across (never up).
io::Image thumbnail(const io::Image& frame, int width) {
  const int factor = std::max(1, (frame.width + width - 1) / width);
  io::Image small(std::max(1, frame.width / factor), std::max(1, frame.height / factor), {"R", "G", "B"});
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += frame.at(x * factor + i, y * factor + j, c);
        small.at(x, y, c) = sum / float(factor * factor);
      }
  return small;
}

bool ffmpegInstalled() {
  return std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
}

// `options`, once the tools they need are there: before the output directory is made.
const FrameWriterOptions& requireVideoEncoder(const FrameWriterOptions& options) {
  if (options.video && !ffmpegInstalled())
    throw io::InputError("--video", "ffmpeg is not installed (apt-get install ffmpeg)");
  return options;
}

}  // namespace

FrameWriter::FrameWriter(fs::path directory, const FrameWriterOptions& options)
    : options_(requireVideoEncoder(options)),
      output_(std::move(directory), "render", options.force, isRenderOutput) {}

bool FrameWriter::isRenderOutput(const std::string& name) {
  static const std::regex frame(R"(frame_[0-9]{4,}\.(png|exr))");
  return std::regex_match(name, frame) || name == "contact_sheet.png" || name == "video.mp4" ||
         name == "timings.json";
}

std::string FrameWriter::frameName(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%04d", index);
  return name;
}

void FrameWriter::write(int index, const io::Image& frame) {
  const fs::path base = output_.stagedPath(frameName(index));
  const io::Image rgb = toDisplay(frame, options_.display);
  output_.underFinalNames([&] {
    io::writePng(fs::path(base) += ".png", rgb);
    if (options_.exr)
      io::writeExr(fs::path(base) += ".exr", frame, io::ExrPixelType::Half, {{"colorspace", "linear"}});
  });
  const int stride = std::max(1, (options_.frames + kMaxSheetCells - 1) / kMaxSheetCells);
  if (index % stride == 0) thumbnails_.push_back(thumbnail(rgb, options_.thumbnailWidth));
}

std::vector<std::string> FrameWriter::finish() {
  std::vector<std::string> files;
  if (!thumbnails_.empty()) {
    const int count = int(thumbnails_.size());
    const int columns = int(std::ceil(std::sqrt(double(count))));
    const int rows = (count + columns - 1) / columns;
    const int cellW = thumbnails_[0].width, cellH = thumbnails_[0].height;
    io::Image sheet(columns * cellW, rows * cellH, {"R", "G", "B"});
    for (int t = 0; t < count; ++t)
      for (int y = 0; y < cellH; ++y)
        for (int x = 0; x < cellW; ++x)
          for (int c = 0; c < 3; ++c)
            sheet.at((t % columns) * cellW + x, (t / columns) * cellH + y, c) = thumbnails_[t].at(x, y, c);
    output_.underFinalNames([&] { io::writePng(output_.stagedPath("contact_sheet.png"), sheet); });
    files.push_back("contact_sheet.png");
  }
  if (options_.video && !thumbnails_.empty()) {
    // yuv420p needs even sides; the scale filter rounds them down. ffmpeg writes the temporary file (-f: its
    // name does not end in .mp4), renamed once ffmpeg has finished.
    io::AtomicFile video(output_.stagedPath("video.mp4"));
    const std::string command =
        "ffmpeg -loglevel error -y -framerate " + std::to_string(options_.fps) + " -i '" +
        output_.stagedPath("frame_%04d.png").string() +
        "' -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -f mp4 '" +
        video.temporaryPath().string() + "'";
    if (std::system(command.c_str()) != 0)
      throw io::InputError((output_.directory() / "video.mp4").string(),
                           "ffmpeg failed to encode the frames");
    video.commit();
    files.push_back("video.mp4");
  }
  return files;
}

}  // namespace sixway::app
