#include "app/frame_writer.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <regex>
#include <set>

#include "io/error.h"
#include "io/exr.h"
#include "io/file_access.h"
#include "io/png.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

// Whether process `pid` has ended: it no longer exists, or it is a zombie (it has exited and only its exit
// status waits for its parent; a parent that killed it on a timeout may never collect it).
bool processEnded(long pid) {
  if (pid <= 0) return false;
  if (::kill(pid_t(pid), 0) != 0) return errno == ESRCH;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const size_t command = line.rfind(')');  // the state follows the command name, which may hold spaces
  return command != std::string::npos && line.compare(command, 3, ") Z") == 0;
}

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

}  // namespace

FrameWriter::FrameWriter(fs::path directory, const FrameWriterOptions& options)
    : directory_(std::move(directory)), options_(options) {
  if (options_.video && !ffmpegInstalled())
    throw io::InputError("--video", "ffmpeg is not installed (apt-get install ffmpeg)");
  staging_ = directory_ / (".render." + std::to_string(getpid()) + ".partial");
  std::error_code error;
  createdDirectory_ = fs::create_directories(directory_, error);
  if (!error) fs::remove_all(staging_, error);  // left by a killed run of a process with this id
  if (!error) fs::create_directory(staging_, error);
  if (error)
    throw io::InputError(directory_.string(), "cannot create the output directory: " + error.message());
}

FrameWriter::~FrameWriter() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  if (createdDirectory_) fs::remove(directory_, ignored);  // only if empty: a failed first run leaves nothing
}

// An error writing a staged file names the file the user will look for, not the hidden staging directory.
void FrameWriter::underFinalNames(const std::function<void()>& write) const {
  try {
    write();
  } catch (const io::InputError& e) {
    std::string message = e.what();
    const std::string staged = staging_.string() + "/";
    if (message.starts_with(staged)) message.replace(0, staged.size(), (directory_ / "").string());
    throw io::InputError(message.substr(0, message.find(": ")), message.substr(message.find(": ") + 2));
  }
}

bool FrameWriter::isRenderOutput(const std::string& name) {
  static const std::regex frame(R"(frame_[0-9]{4,}\.(png|exr))");
  return std::regex_match(name, frame) || name == "contact_sheet.png" || name == "video.mp4" ||
         name == "timings.json";
}

void FrameWriter::commit() {
  std::set<std::string> staged;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(staging_, error)) staged.insert(entry.path().filename());
  for (const std::string& name : staged) {
    fs::rename(staging_ / name, directory_ / name, error);
    if (error)
      throw io::InputError((directory_ / name).string(), "cannot move the new file in: " + error.message());
  }
  std::vector<fs::path> earlier;
  for (const auto& entry : fs::directory_iterator(directory_, error)) {
    const std::string name = entry.path().filename();
    if (!staged.contains(name) && isRenderOutput(name) && entry.is_regular_file())
      earlier.push_back(entry.path());
  }
  for (const fs::path& path : earlier) fs::remove(path, error);
  fs::remove(staging_, error);
  committed_ = true;
  removeStagingOfKilledRuns();
}

// A render killed half-way leaves its hidden staging directory; the next render into the directory removes
// it once its process has ended.
void FrameWriter::removeStagingOfKilledRuns() const {
  static const std::regex name(R"(\.render\.([0-9]{1,9})\.partial)");
  io::removeNumberedEntries(directory_, name, fs::file_type::directory, processEnded);
}

std::string FrameWriter::frameName(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%04d", index);
  return name;
}

void FrameWriter::write(int index, const io::Image& frame) {
  const fs::path base = staging_ / frameName(index);
  const io::Image rgb = toDisplay(frame, options_.display);
  underFinalNames([&] {
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
    underFinalNames([&] { io::writePng(staging_ / "contact_sheet.png", sheet); });
    files.push_back("contact_sheet.png");
  }
  if (options_.video && !thumbnails_.empty()) {
    // yuv420p needs even sides; the scale filter rounds them down. ffmpeg writes the temporary file (-f: its
    // name does not end in .mp4), renamed once ffmpeg has finished.
    io::AtomicFile video(staging_ / "video.mp4");
    const std::string command =
        "ffmpeg -loglevel error -y -framerate " + std::to_string(options_.fps) + " -i '" +
        (staging_ / "frame_%04d.png").string() +
        "' -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -f mp4 '" +
        video.temporaryPath().string() + "'";
    if (std::system(command.c_str()) != 0)
      throw io::InputError((directory_ / "video.mp4").string(), "ffmpeg failed to encode the frames");
    video.commit();
    files.push_back("video.mp4");
  }
  return files;
}

}  // namespace sixway::app
