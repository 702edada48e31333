#include "app/dataset_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace sixway::app {

std::string formatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld", s / 60, s % 60);
  return text;
}

DatasetProgress::DatasetProgress(int sequences, long totalFrames)
    : sequences_(sequences),
      totalFrames_(std::max(1L, totalFrames)),
      terminal_(isatty(fileno(stdout)) != 0),
      start_(std::chrono::steady_clock::now()) {}

double DatasetProgress::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string DatasetProgress::status(int sequence, int ordinal, int frame, int frames) const {
  const double fraction = double(doneFrames_) / double(totalFrames_);
  const double elapsed = elapsedSeconds();
  // Every frame of every sequence counts the same: warm-up frames are cheaper than sampled ones, but each
  // sequence mixes them alike, so the rate settles after the first sequence.
  const std::string eta = doneFrames_ > 0 ? formatDuration(elapsed / fraction - elapsed) : "?";
  char text[160];
  std::snprintf(text, sizeof(text), "%3.0f%% sequence %d (%d/%d), frame %d/%d, %s elapsed, ETA %s",
                100 * fraction, sequence, ordinal, sequences_, frame, frames, formatDuration(elapsed).c_str(),
                eta.c_str());
  return text;
}

void DatasetProgress::frameDone(int sequence, int ordinal, int frame, int frames) {
  ++doneFrames_;
  if (terminal_) {
    constexpr int kWidth = 24;
    const int filled = int(kWidth * doneFrames_ / totalFrames_);
    std::printf("\r  [%s%s] %s\033[K", std::string(filled, '#').c_str(),
                std::string(kWidth - filled, '.').c_str(), status(sequence, ordinal, frame, frames).c_str());
    barShown_ = true;
  } else {
    const int tenth = int(10 * doneFrames_ / totalFrames_);
    if (tenth == lastTenth_ && frame < frames) return;
    lastTenth_ = tenth;
    std::printf("  %s\n", status(sequence, ordinal, frame, frames).c_str());
  }
  std::fflush(stdout);
}

void DatasetProgress::endLine() {
  if (barShown_) std::printf("\n");
  barShown_ = false;
  std::fflush(stdout);
}

void DatasetProgress::note(const std::string& line) {
  std::printf("%s  %s\n", barShown_ ? "\r\033[K" : "", line.c_str());
  barShown_ = false;
  std::fflush(stdout);
}

}  // namespace sixway::app
